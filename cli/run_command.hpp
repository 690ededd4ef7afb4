#pragma once
// `motus run SCENE`: integrate one scene with one integrator and report energy,
// momentum, work and the final state (human summary or --json), optionally writing
// the trajectory as CSV.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace motus::cli {

struct RunOptions {
  std::string scene;
  std::optional<std::string> integrator;
  std::optional<double> dt, duration, rtol, atol;
  std::optional<long> steps;
  std::vector<std::string> sets;
  std::vector<std::string> plugins;  // --plugin
  std::string trajectory;
  bool overwrite = false;
  bool json = false;
  int repeats = 0;  // runs timed, the first the one reported (0: the default, compare::auto_rounds)
};

CLI::App* add_run_command(CLI::App& app, RunOptions& options);
int run_command(const RunOptions& options);

}  // namespace motus::cli
