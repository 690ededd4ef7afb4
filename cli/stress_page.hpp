#pragma once
// The page of `motus stress`: one CSV per section, the figures (plot/, gnuplot: PNG and SVG),
// summary.json and index.html, written into a folder (docs/cli.md, "motus stress").
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "stress_measures.hpp"

namespace motus::cli::stress {

struct Report {
  std::string scene_name, scene_file, description;
  int dimensions = 0;
  long bodies = 0;
  double dt = 0;
  Settings settings;
  std::optional<double> omega;  // an undamped harmonic oscillator's ω, where theory applies
  std::string stiffness_knob;
  // A damper or drag takes energy out by design: the energy's change is then not all error.
  bool loses_energy_by_design = false;
  std::vector<std::string> sections;                            // measured, in order
  std::vector<std::pair<std::string, std::string>> not_applied;  // section, why not
  std::vector<std::pair<std::string, std::string>> cannot_run;   // integrator, why not
  std::vector<StabilityResult> stability;
  std::vector<DriftResult> drift;
  std::vector<StiffnessResult> stiffness;
  std::vector<MassRatioRow> mass_ratio;
  std::vector<SpeedRow> speed;
  std::vector<StickRow> sticks;
  // What of a section that applies was measured (the rest is in not_applied, with why):
  bool mass_ratio_scene = true;  // the mass-ratio rows of the scene itself (two balls or more)
  bool speed_scene = true;       // the speed rows of the scene itself (a body moves)
  bool speed_container = true;   // their balls outside a container (the scene has a box)
  std::vector<std::string> stick_variants_measured;
};

// A table's failures: the cell says "failed (k)", and the message is note k below the table (a
// message cut to fit a cell, 100 characters, ran over three columns). The same message is one note.
class FailureNotes {
public:
  std::string cell(const std::string& message);  // "failed (k)"
  const std::vector<std::string>& notes() const { return notes_; }

private:
  std::vector<std::string> notes_;
};

// The first factor of stiffness_factors() at which theory says the integrator blows up (0: none
// known), for an undamped harmonic oscillator: ωh beyond its limit.
double theory_first_failure(const Report& report, Integrator integrator);

nlohmann::json summary_json(const Report& report);
// Writes everything into `folder`; returns "" or one line about the plots (gnuplot missing or failed).
std::string write_page(const std::string& folder, const Report& report);

}  // namespace motus::cli::stress
