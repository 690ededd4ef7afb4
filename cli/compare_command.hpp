#pragma once
// `motus compare SCENE`: the same scene in motus, Box2D and Bullet, side by side — a
// table of energy and momentum drift, penetration, constraint error and time per step,
// and a report folder with the metrics, plots and index.html.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace motus::cli {

struct CompareOptions {
  std::string scene;
  std::vector<std::string> engines;  // none given: motus, each plug-in's column, box2d, bullet
  std::optional<std::string> integrator;
  std::optional<double> dt, duration;
  std::vector<std::string> sets;
  std::vector<std::string> plugins;  // --plugin
  std::string out;
  long samples = 200;
  int repeats = 0;  // timing rounds (0: the default, compare::auto_rounds)
  bool json = false;
  bool render = false;
  std::string size = "480x360";  // each panel, with --render
  double fps = 30;               // frames per simulated second, with --render
};

CLI::App* add_compare_command(CLI::App& app, CompareOptions& options);
int compare_command(const CompareOptions& options);

}  // namespace motus::cli
