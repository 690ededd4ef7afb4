#include "motus/render/video.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "motus/process/run_program.hpp"
#include "motus/render/image.hpp"

namespace motus::render {

std::optional<VideoFormat> video_format_from_name(const std::string& name) {
  if (name == "mp4") return VideoFormat::mp4;
  if (name == "gif") return VideoFormat::gif;
  return std::nullopt;
}

void encode_video(const std::string& frame_pattern, double fps, const std::string& out_path, VideoFormat format) {
  const std::string ffmpeg = process::find_program("ffmpeg");
  if (ffmpeg.empty())
    throw RenderError("ffmpeg not found on PATH: --video needs it (install the Debian package ffmpeg)");
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  // ffmpeg reads every % of the input as the pattern's: the folder's are written %%. (The folder
  // is copied as it is escaped: escaping in place moved the name on, and a folder "q%%" lost one.)
  const size_t name = frame_pattern.rfind('/');
  std::string pattern;
  for (size_t at = 0; at < frame_pattern.size(); ++at) {
    pattern += frame_pattern[at];
    if (frame_pattern[at] == '%' && name != std::string::npos && at < name) pattern += '%';
  }
  // A relative path is given as ./PATH: ffmpeg takes "-lead/…" for an option and "a:b/…" for a
  // protocol's URL (the render failed after drawing every frame).
  auto as_file = [](const std::string& path) { return path.starts_with('/') ? path : "./" + path; };
  std::vector<std::string> args{ffmpeg, "-nostdin", "-y", "-loglevel", "error", "-framerate", rate, "-i", as_file(pattern)};
  if (format == VideoFormat::mp4) {
    args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                             "-movflags", "+faststart"});
  } else {
    args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse=dither=bayer:bayer_scale=5",
                             "-loop", "0"});
  }
  args.push_back(as_file(out_path));
  // What ffmpeg says (at -loglevel error, only errors) goes to a file of its own and is read back:
  // it can report an error and still exit 0 (a full disk while it writes the trailer leaves a
  // video that does not play), and its lines are not motus's one-line message.
  // (Beside the video, not in /tmp: what a process stopped at once leaves stays in its own folder.)
  const std::string beside = std::filesystem::path(out_path).parent_path().string();
  std::string log = (beside.empty() ? std::string(".") : beside) + "/.ffmpeg-messages-XXXXXX";
  const int log_fd = ::mkstemp(log.data());
  if (log_fd < 0) log.clear();  // (then its messages go where motus's do)
  else ::close(log_fd);
  struct Removed {  // (however this function is left)
    const std::string& file;
    ~Removed() {
      if (!file.empty()) ::unlink(file.c_str());
    }
  } removed{log};
  const process::Outcome ffmpeg_run = process::run_program(args, "", log);
  std::string said;
  if (!log.empty()) {
    std::ifstream in(log);
    std::getline(in, said);  // the first line: the error, as ffmpeg words it
  }
  if (!ffmpeg_run.started) throw RenderError(ffmpeg_run.not_started("ffmpeg", ffmpeg));
  if (!ffmpeg_run.ok() || !said.empty())
    throw std::runtime_error("ffmpeg failed to write " + out_path + " (" +
                             (!said.empty()           ? "it said: " + said
                              : ffmpeg_run.signal     ? "signal " + std::to_string(ffmpeg_run.signal)
                                                      : "exit status " + std::to_string(ffmpeg_run.status)) +
                             ")");
}

}  // namespace motus::render
