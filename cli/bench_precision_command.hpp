#pragma once
// `motus bench precision SCENE`: the course's "run time against error" (docs/course.md, section 5).
// For each integrator — motus's own, a plug-in's, and with --peers Boost.Odeint's steppers on the same
// right-hand side, Box2D and Bullet — sweep the step (fixed-step methods) or the tolerance (adaptive
// ones), measure the error at the end against the scene's exact or reference solution, the
// derivative evaluations and the run time (the fastest of several runs); read every curve at target
// errors; write the table, the work–precision diagrams and index.html into a run folder
// (precision/, docs/cli.md).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace motus::cli {

struct BenchPrecisionOptions {
  std::string scene;
  std::vector<std::string> integrators;
  std::vector<std::string> peers;     // --peers odeint,box2d,bullet
  std::vector<std::string> sets;
  std::vector<std::string> plugins;   // --plugin
  std::vector<double> targets;        // --targets (default 1e-4 … 1e-10)
  int levels = 8;
  int per_decade = 3;
  int repeats = 9;
  std::optional<double> duration;
  std::string out;  // the run folder (default: a new one under runs/)
  std::string csv;  // also the table here
  bool overwrite = false;
};

CLI::App* add_bench_precision_command(CLI::App& bench, BenchPrecisionOptions& options);
int bench_precision_command(const BenchPrecisionOptions& options);

}  // namespace motus::cli
