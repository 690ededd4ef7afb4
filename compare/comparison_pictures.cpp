#include "comparison_pictures.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "motus/render/canvas.hpp"
#include "motus/render/compose.hpp"
#include "motus/render/draw.hpp"
#include "motus/render/video.hpp"

namespace fs = std::filesystem;

namespace motus::compare {
namespace {

// A run's frames as the renderer's recording: [x; v] per frame, with its energy.
render::Recording recording_of(const EngineRun& run) {
  render::Recording recording;
  std::vector<double> state;
  for (size_t k = 0; k < run.frames.size(); ++k) {
    const Snapshot& s = run.frames[k];
    state.assign(s.x.begin(), s.x.end());
    state.insert(state.end(), s.v.begin(), s.v.end());
    recording.add(s.t, state, run.frame_energies[k]);
  }
  return recording;
}

}  // namespace

ComparisonPictures draw_comparison(const std::string& folder, const SceneDescription& scene,
                                   const std::vector<EngineRun>& runs, int width, int height, double fps) {
  ComparisonPictures pictures;
  render::Canvas canvas(width, height);
  const render::Viewport view = canvas.full();

  std::vector<render::Recording> recordings;
  for (const auto& run : runs) recordings.push_back(run.supported ? recording_of(run) : render::Recording{});
  const render::Recording* reference = nullptr;  // the first engine that ran (motus, when asked for)
  for (size_t e = 0; e < runs.size() && !reference; ++e)
    if (runs[e].supported) reference = &recordings[e];
  if (!reference) return pictures;
  // One camera and one ground for every panel and every frame, so the panels compare.
  const render::Camera camera = render::fit_camera(scene, *reference, view);
  render::DrawOptions options;
  render::fit_ground(scene, *reference, options);

  std::vector<std::string> labels;
  for (const auto& run : runs) labels.push_back(run.version.empty() ? run.engine : run.version);

  const std::string frames_folder = folder + "/frames";
  fs::create_directories(frames_folder);
  const size_t frames = reference->size();
  std::vector<render::Image> sheet;
  const std::vector<size_t> sheet_frames = {0, frames / 2, frames - 1};
  std::vector<std::string> sheet_labels;
  render::Image panel;
  for (size_t k = 0; k < frames; ++k) {
    std::vector<render::Image> panels;
    for (size_t e = 0; e < runs.size(); ++e) {
      if (runs[e].supported && k < recordings[e].size()) {
        render::draw_frame(canvas, view, scene, recordings[e], k, camera, options, runs[e].engine);
      } else {
        canvas.clear(options.background);
        int y = height / 2 - 10 * static_cast<int>(runs[e].unsupported.size());
        for (const auto& line : runs[e].unsupported) {
          canvas.text(12, y, line);
          y += 22;
        }
      }
      canvas.image(panel);
      panels.push_back(panel);
    }
    const render::Image row = render::compose_side_by_side(panels, labels);
    render::write_png(fmt::format("{}/frame_{:05d}.png", frames_folder, k), row);
    if (std::find(sheet_frames.begin(), sheet_frames.end(), k) != sheet_frames.end()) {
      sheet.push_back(row);
      sheet_labels.push_back(fmt::format("t = {:.3g} s", reference->times[k]));
    }
  }
  pictures.frames = static_cast<long>(frames);
  pictures.contact_sheet = "contact_sheet.png";
  render::write_png(folder + "/" + pictures.contact_sheet, render::contact_sheet(sheet, 1, sheet_labels));
  if (render::find_program("ffmpeg").empty()) {
    pictures.warning = "video skipped: ffmpeg not found on PATH (install the Debian package ffmpeg)";
  } else {
    pictures.video = "comparison.mp4";
    render::encode_video(frames_folder + "/frame_%05d.png", fps, folder + "/" + pictures.video, render::VideoFormat::mp4);
  }
  return pictures;
}

}  // namespace motus::compare
