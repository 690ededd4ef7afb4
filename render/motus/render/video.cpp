#include "motus/render/video.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "motus/render/image.hpp"

extern char** environ;

namespace motus::render {

std::optional<VideoFormat> video_format_from_name(const std::string& name) {
  if (name == "mp4") return VideoFormat::mp4;
  if (name == "gif") return VideoFormat::gif;
  return std::nullopt;
}

std::string find_program(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) dir.assign(1, '.');  // (not = ".": GCC 12 warns falsely, PR105651)
    const std::filesystem::path candidate = std::filesystem::path(dir) / program;
    std::error_code error;
    if (std::filesystem::is_regular_file(candidate, error) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate.string();
  }
  return "";
}

void encode_video(const std::string& frame_pattern, double fps, const std::string& out_path, VideoFormat format) {
  const std::string ffmpeg = find_program("ffmpeg");
  if (ffmpeg.empty())
    throw RenderError("ffmpeg not found on PATH: --video needs it (install the Debian package ffmpeg)");
  char rate[32];
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  std::vector<std::string> args{ffmpeg, "-nostdin", "-y", "-loglevel", "error", "-framerate", rate, "-i", frame_pattern};
  if (format == VideoFormat::mp4) {
    args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                             "-movflags", "+faststart"});
  } else {
    args.insert(args.end(), {"-vf", "split[a][b];[a]palettegen=stats_mode=diff[p];[b][p]paletteuse=dither=bayer:bayer_scale=5",
                             "-loop", "0"});
  }
  args.push_back(out_path);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (const int error = posix_spawn(&pid, ffmpeg.c_str(), nullptr, nullptr, argv.data(), environ); error != 0)
    throw RenderError("ffmpeg (" + ffmpeg + ") could not be started");
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) throw std::runtime_error("waiting for ffmpeg failed");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("ffmpeg failed to write " + out_path + " (exit status " +
                             std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
}

}  // namespace motus::render
