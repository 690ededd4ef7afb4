#pragma once
// What `motus compare` leaves behind in its folder: the metrics as CSV and JSON, plots
// of energy and momentum against time (gnuplot), and an index.html that opens
// straight from the file system.
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "motus/compare/comparison.hpp"
#include "motus/compare/initial_overlap.hpp"

namespace motus::compare {

// How busy the machine was while the engines were timed. The rounds are CPU time, so a wait for a
// core is not counted; but with more runnable work than cores a round shares the caches and the
// memory bandwidth and is cut into slices, more or less as the load comes and goes, and taking
// turns cannot make rounds of very different lengths meet the same load (an audit's ball_gas with
// 10,000 balls: motus's round took 0.04 s, Bullet's 23 s), so the ratios between engines may be off.
struct MachineLoad {
  // The 1-minute load average as the timing rounds began and as they ended (NaN: not known).
  double at_start = NAN, at_end = NAN;
  long cores = 0;  // online (0: not known)
};

struct ReportContext {
  const SceneDescription* scene = nullptr;  // what was run (the definitions, the exact answer, the replay)
  std::string scene_name, scene_file, description;
  std::string integrator;  // as shown: "symplectic-euler (student:symplectic-euler in student)" for a plug-in's
  std::string method;      // what motus's own column ran, by its name alone ("symplectic-euler"; "": as integrator)
  double dt = 0, duration = 0;
  long samples = 0;  // metric samples over the run
  int dimensions = 2;
  long bodies = 0;
  int repeats = 0;  // timing rounds
  std::string video, contact_sheet;  // file names in the folder (--render), or ""
  std::string first_and_last;        // the engines side by side at the start and the end (file name), or ""
  std::string pictures_note;         // why --render's pictures (or its video) are missing, or ""
  bool momentum_conserved = false;          // the scene keeps it (no walls, no outside force)
  bool angular_momentum_conserved = false;  // about the origin
  MachineLoad load;                         // while the engines were timed (unknown: NaN and 0)
  InitialOverlap initial_overlap;           // the scene's own, as written (found once: O(N log N))
};

// Whether a scene keeps its total momentum and its angular momentum about the origin exactly
// (so that a plot of their change shows each engine's error, not the physics): no walls, no pins,
// and only forces between bodies — or, for the angular momentum, central about the origin.
struct Conserved {
  bool momentum = false, angular_momentum = false;
};
Conserved conserved_quantities(const SceneDescription& scene);

// A time per step in microseconds as the table and the report both show it: three significant
// figures without an exponent, whole microseconds from 100 on (0.0784, 0.709, 5.38, 2734; two
// decimals made kepler's 0.0408 and 0.64 read as 16x beside 15.68x, and 2.73e+03 in the report
// was the terminal's 2734).
std::string microseconds_text(double us);

// The summary of every engine as one JSON object (also what --json prints).
nlohmann::json summary_json(const ReportContext& context, const std::vector<EngineRun>& runs);

// Draws the report's figures into `folder` (which must exist): energy, and momentum and angular
// momentum where the scene keeps them, PNG and SVG, by one gnuplot run, with figures.gp and
// figures.dat. It reads nothing of the pictures (context's first_and_last, video, …), so compare
// draws them meanwhile. Returns a line to show the user when the plots could not be made, else "".
std::string draw_figures(const std::string& folder, const ReportContext& context, const std::vector<EngineRun>& runs);

// Writes metrics.csv, summary.json, the replay (replay.js, replay-data.js; when context.scene is
// set) and index.html into `folder`, the page showing the figures draw_figures drew there, or
// `plots_line` — draw_figures's answer — where it could not.
void write_report(const std::string& folder, const ReportContext& context, const std::vector<EngineRun>& runs,
                  const std::string& plots_line);

}  // namespace motus::compare
