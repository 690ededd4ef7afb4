#pragma once
// `motus stress SCENE`: the course's stability stress test as a command — the largest stable
// step of each integrator against theory, the energy drift over a long run, stiffness raised by
// decades, collisions between very different masses, balls moving many radii per step, sticks
// between very different masses — as far as each applies to the scene, printed as tables and
// written as a page (index.html, CSV, SVG and PNG plots). docs/cli.md, "motus stress".
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace motus::cli {

struct StressOptions {
  std::string scene;
  std::vector<std::string> integrators;  // none given: every built-in integrator that can run the scene
  std::vector<std::string> sets;
  std::string out;
  long steps = 10000;         // a stability or stiffness trial
  long drift_steps = 100000;  // the long run
  double energy_factor = 1e6;
  double duration = 1;        // a mass-ratio or sticks run, s
};

CLI::App* add_stress_command(CLI::App& app, StressOptions& options);
int stress_command(const StressOptions& options);

}  // namespace motus::cli
