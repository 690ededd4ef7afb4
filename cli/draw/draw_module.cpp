// motus-draw.so: the drawing half of `motus render` and `motus compare`, loaded at
// run time (see draw_api.hpp). It turns recorded states into PNG frames, videos and contact
// sheets with render/ (OSMesa, libpng, FreeType, ffmpeg).
#include <fmt/format.h>

#include <algorithm>
#include <exception>
#include <filesystem>
#include <new>

#include "draw_api.hpp"
#include "motus/plot/figure.hpp"
#include "motus/process/run_program.hpp"
#include "motus/render/canvas.hpp"
#include "motus/render/compose.hpp"
#include "motus/render/draw.hpp"
#include "motus/render/text.hpp"
#include "motus/render/video.hpp"

static_assert(motus::draw::RenderJob::kMostTrailedBodies == motus::render::kMostTrailedBodies,
              "motus render says which scenes get trails; the drawing draws them");

namespace fs = std::filesystem;

namespace motus::draw {
namespace {

// A run's states as the drawing reads them: moved, not copied (a comparison of 40,000 balls kept a
// third copy of a gigabyte of them).
render::Recording recording_of(Frames&& frames) {
  render::Recording recording;
  recording.times = std::move(frames.times);
  recording.states = std::move(frames.states);
  recording.energies = std::move(frames.energies);
  frames = {};
  return recording;
}

// Runs `work`, turning any exception into its one-line message (kOutOfMemory when memory ran out).
template <class Work>
std::string guarded(Work&& work) {
  try {
    work();
    return "";
  } catch (const std::bad_alloc&) {
    return kOutOfMemory;
  } catch (const std::exception& e) {
    return e.what();
  }
}

std::string check(int width, int height, int supersample) {
  return guarded([&] {
    render::Canvas canvas(width, height, supersample);
    render::Font::default_font();
  });
}

std::string render_frames(const RenderJob& job) {
  return guarded([&] {
    render::Canvas canvas(job.width, job.height, job.supersample);
    const render::Recording recording = recording_of(std::move(*job.frames));
    // One camera for the whole run, so nothing jumps.
    const render::Viewport view = canvas.full();
    const render::Camera camera = render::fit_camera(*job.scene, recording, view);
    render::DrawOptions options;
    options.trails = job.trails;
    options.velocity_arrows = job.arrows;
    if (job.frame_index.size() >= 2)
      options.frame_interval = recording.times[job.frame_index[1]] - recording.times[job.frame_index[0]];
    render::fit_ground(*job.scene, recording, options);
    render::Image image;
    for (size_t k = 0; k < job.frame_index.size(); ++k) {
      render::draw_frame(canvas, view, *job.scene, recording, job.frame_index[k], camera, options, job.note);
      canvas.image(image);
      render::write_png((fs::path(job.folder) / fmt::format("frame_{:05d}.png", k)).string(), image);
      if (job.frame_done) job.frame_done(static_cast<long>(k) + 1);
    }
  });
}

std::string encode_video(const std::string& pattern, double fps, const std::string& out, const std::string& format) {
  return guarded([&] {
    const auto f = render::video_format_from_name(format);
    if (!f) throw std::invalid_argument("unknown video format \"" + format + "\" (mp4 or gif)");
    render::encode_video(pattern, fps, out, *f);
  });
}

// The same instants of every engine as labelled panels side by side, each with the time and
// its own energy drift, as PNG frames, a video (ffmpeg) and a contact sheet.
std::string draw_comparison(ComparisonJob& job, ComparisonPictures& pictures) {
  pictures = {};
  // (render::write_png throws RenderError only when the file cannot be written)
  const auto write_png = [&](const std::string& path, const render::Image& image) {
    try {
      render::write_png(path, image);
    } catch (const render::RenderError&) {
      pictures.write_failed = true;
      throw;
    }
  };
  return guarded([&] {
    render::Canvas canvas(job.width, job.height);
    const render::Viewport view = canvas.full();
    std::vector<render::Recording> recordings;
    for (auto& panel : job.panels) recordings.push_back(recording_of(std::move(panel.frames)));
    const render::Recording* reference = nullptr;  // the first engine that ran (motus, when asked for)
    for (size_t e = 0; e < job.panels.size() && !reference; ++e)
      if (job.panels[e].unsupported.empty()) reference = &recordings[e];
    if (!reference || reference->size() == 0) return;
    // One camera and one ground for every panel and every frame, so the panels compare: fitted to
    // every engine's bodies (Bullet's rope, stretched to twice its length, ran off the bottom of a
    // view fitted to motus's alone, under the scale bar), but to none that goes far beyond the first
    // engine's (in_a_shared_view): a peer that blew up would shrink the others to a dot. Its panel
    // says its bodies leave the view.
    std::vector<bool> in_view;
    for (const auto& panel : job.panels) in_view.push_back(panel.unsupported.empty());
    in_view = render::in_a_shared_view(*job.scene, recordings, static_cast<size_t>(reference - recordings.data()), in_view);
    std::vector<const render::Recording*> everyone;
    for (size_t e = 0; e < recordings.size(); ++e)
      if (in_view[e]) everyone.push_back(&recordings[e]);
    const render::Camera camera = render::fit_camera(*job.scene, everyone, view);
    render::DrawOptions options;
    options.first_body_colour = plot::kEngineColour::first_free;  // (after the engines' colours, as the replay's)
    render::fit_ground(*job.scene, everyone, options);
    if (reference->size() >= 2) options.frame_interval = reference->times[1] - reference->times[0];

    std::vector<std::string> labels;
    for (size_t e = 0; e < job.panels.size(); ++e) {
      const Panel& panel = job.panels[e];
      labels.push_back((panel.label.empty() ? panel.engine : panel.label) +
                       (panel.unsupported.empty() && !in_view[e] ? " (its bodies go out of this view)" : ""));
    }
    const std::string frames_folder = job.folder + "/frames";
    if (!job.first_and_last_only) fs::create_directories(frames_folder);
    const size_t frames = reference->size();
    std::vector<render::Image> sheet, ends;  // (ends: the first and the last instant, in every report)
    const std::vector<size_t> sheet_frames{0, frames / 2, frames - 1};  // (the contact sheet's; not when first_and_last_only)
    std::vector<std::string> sheet_labels;
    render::Image panel_image;
    for (size_t k = 0; k < frames; ++k) {
      if (job.first_and_last_only && k != 0 && k + 1 != frames) continue;
      std::vector<render::Image> panels;
      for (size_t e = 0; e < job.panels.size(); ++e) {
        const Panel& panel = job.panels[e];
        if (panel.unsupported.empty() && k < recordings[e].size()) {
          render::draw_frame(canvas, view, *job.scene, recordings[e], k, camera, options, panel.engine);
        } else {
          canvas.clear(options.background);
          int y = job.height / 2 - 10 * static_cast<int>(panel.unsupported.size());
          for (const auto& line : panel.unsupported) {
            canvas.text(12, y, line);
            y += 22;
          }
        }
        canvas.image(panel_image);
        panels.push_back(panel_image);
      }
      const render::Image row = render::compose_side_by_side(panels, labels);
      if (!job.first_and_last_only) write_png(fmt::format("{}/frame_{:05d}.png", frames_folder, k), row);
      if (k == 0 || k + 1 == frames) ends.push_back(row);
      if (!job.first_and_last_only && std::find(sheet_frames.begin(), sheet_frames.end(), k) != sheet_frames.end()) {
        sheet.push_back(row);
        sheet_labels.push_back(fmt::format("t = {:.3g} s", reference->times[k]));
      }
      if (job.progress) job.progress(static_cast<long>(k) + 1, static_cast<long>(frames));
    }
    pictures.frames = static_cast<long>(frames);
    pictures.first_and_last = "first_and_last.png";
    std::vector<std::string> end_labels{fmt::format("t = {:.3g} s", reference->times[0])};
    if (frames > 1) end_labels.push_back(fmt::format("t = {:.3g} s", reference->times[frames - 1]));
    write_png(job.folder + "/" + pictures.first_and_last, render::contact_sheet(ends, 1, end_labels));
    if (job.first_and_last_only) return;
    pictures.contact_sheet = "contact_sheet.png";
    write_png(job.folder + "/" + pictures.contact_sheet, render::contact_sheet(sheet, 1, sheet_labels));
    if (process::find_program("ffmpeg").empty()) {
      pictures.warning = "video skipped: ffmpeg not found on PATH (install the Debian package ffmpeg)";
    } else {
      // A video ffmpeg fails to make (a full disk, its error at exit 0) fails the run, as a picture
      // that cannot be written does and as `motus render --video` does: --render asked for it, and
      // a report without it, exit 0, would pass for whole. (Without ffmpeg at all, the video is
      // skipped with a warning, above: the frames and the sheet are what most come for.)
      try {
        render::encode_video(frames_folder + "/frame_%05d.png", job.fps, job.folder + "/comparison.mp4",
                             render::VideoFormat::mp4);
        pictures.video = "comparison.mp4";
      } catch (const std::bad_alloc&) {
        throw;  // (out of memory fails the run, as anywhere else)
      } catch (const std::exception& e) {
        pictures.write_failed = true;
        throw std::runtime_error(std::string("the video could not be made: ") + e.what());
      }
    }
  });
}

}  // namespace
}  // namespace motus::draw

extern "C" __attribute__((visibility("default"))) const motus::draw::Api* motus_draw_api() {
  static const motus::draw::Api api{motus::draw::kApiVersion,       motus::draw::check,
                                    motus::draw::render_frames,       motus::draw::encode_video,
                                    motus::draw::draw_comparison,     motus::process::kill_running_programs,
                                    motus::process::stop_running_programs};
  return &api;
}
