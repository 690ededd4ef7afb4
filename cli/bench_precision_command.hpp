#pragma once
// `motus bench precision SCENE`: the course's "run time against error" (docs/course.md, section 5). For each
// integrator, sweep the step (fixed-step methods) or the tolerance (adaptive ones) and
// measure the final-time error against the scene's exact or reference solution, the
// derivative evaluations and the run time (the minimum of several runs).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace motus::cli {

struct BenchPrecisionOptions {
  std::string scene;
  std::vector<std::string> integrators;
  std::vector<std::string> sets;
  std::vector<std::string> plugins;  // --plugin
  int levels = 6;
  int repeats = 3;
  std::optional<double> duration;
  std::string csv;
  bool overwrite = false;
};

CLI::App* add_bench_precision_command(CLI::App& bench, BenchPrecisionOptions& options);
int bench_precision_command(const BenchPrecisionOptions& options);

}  // namespace motus::cli
