#pragma once
// `motus render SCENE --out DIR`: simulate a scene and draw it as PNG frames (and,
// with --video, one MP4 or GIF through ffmpeg). See docs/render.md.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace motus::cli {

struct RenderOptions {
  std::string scene;
  std::string out;
  std::string size = "640x480";
  // Frames per simulated second (year); unset: 30 a second of video at the playing speed, or one a
  // step of a fixed-step integrator whose dt is longer than that (render_command.cpp, frame_rate).
  std::optional<double> fps;
  // Simulated seconds (years) a second of video; unset: 1, or a run longer than 20 s plays in 20 s.
  std::optional<double> speed;
  std::optional<double> duration;
  std::optional<std::string> integrator;
  std::vector<std::string> sets;
  std::vector<std::string> plugins;  // --plugin
  std::string video;  // "", "mp4" or "gif"
  bool overwrite = false;
  bool trails = false;
  bool arrows = false;
  int supersample = 2;
};

CLI::App* add_render_command(CLI::App& app, RenderOptions& options);
int render_command(const RenderOptions& options);

}  // namespace motus::cli
