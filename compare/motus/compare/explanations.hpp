#pragma once
// What the comparison's numbers mean, in words: the definition of every column, the exact answer
// where the scene has one (and how far each engine ended from it), and one sentence, made from
// the measured numbers, saying what to notice. The report and the terminal table both use it.
#include <optional>
#include <string>
#include <vector>

#include "motus/compare/comparison.hpp"
#include "motus/compare/initial_overlap.hpp"
#include "motus/compare/report.hpp"
#include "motus/scene.hpp"

namespace motus::compare {

struct ColumnDefinition {
  std::string column;   // as the table heads it
  std::string meaning;  // what it is and how it is computed, one or two sentences
};

// The columns of the summary table, defined for this scene (whether it keeps its momentum,
// whether it has an exact answer, how many samples the maxima are over).
// `energy_in_joules`: the scene starts with E₀ = 0 (comparison.hpp's energy_in_joules).
// `overlap`: the scene's own (initial_overlap), which every engine's penetration column counts.
std::vector<ColumnDefinition> column_definitions(const SceneDescription& scene, long samples, bool momentum_conserved,
                                                 bool energy_in_joules = false, const InitialOverlap& overlap = {});

// The exact state at the end of the run and each engine's final velocities beside it.
struct ExactAnswer {
  double t = 0;
  std::string source;  // "the free-flight solution (event by event)", "the harmonic oscillator", ...
  int dimensions = 2;
  std::vector<std::vector<double>> position, velocity;  // per body (up to kShownBodies)
  struct Engine {
    std::string engine;
    std::vector<std::vector<double>> velocity;  // per body shown
    double worst_speed_error = 0;               // max over all bodies of |v − v_exact|, m/s
    int worst_body = 0;
    double worst_position_error = 0;            // max over all bodies of |x − x_exact| at the end, m
  };
  std::vector<Engine> engines;  // the supported ones, in run order
  long bodies = 0;              // in the scene (the table shows the first kShownBodies)
  static constexpr int kShownBodies = 8;
};

// nullopt when the scene has no exact state at the run's end (none declared, or unknown there).
std::optional<ExactAnswer> exact_answer(const SceneDescription& scene, const std::vector<EngineRun>& runs);

// One sentence from the measured numbers: against the exact answer where there is one, else the
// sticks' lengths, else the energy (kept exactly by the scene, or lost by design).
std::string what_to_notice(const SceneDescription& scene, const std::vector<EngineRun>& runs,
                           const std::optional<ExactAnswer>& exact);

// Whether the scene keeps its energy exactly (every restitution 1, no damping, no drag): then an
// energy change is an engine's error; otherwise it is partly the physics.
bool conserves_energy(const SceneDescription& scene);

// The unit of the bodies' coordinates and of distances between them: "rad" for a pendulum (its
// coordinate is its angle θ), else "m".
std::string coordinate_unit(const SceneDescription& scene);

// The time a run ends at (`start` + steps·dt) when it reads otherwise than start + duration: the
// step count is rounded up to whole steps (motus::fixed_step_count), so kepler's 2π s at dt = 0.01 s
// takes 629 steps and ends at 6.29 s. nullopt when the two read the same ({:g}).
std::optional<double> end_past_duration(double start, double duration, double dt);

// What the momentum columns measure: "momentum", p = Σ m v — or, where the coordinate is an angle θ
// (coordinate_unit "rad"), "m·θ'", the mass times the angular velocity, which is no momentum.
std::string momentum_quantity(const SceneDescription& scene);

// The note under the table for its momentum column, whose heading is then marked "*", when that
// column is not an engine's error: the scene does not keep its momentum (`momentum_conserved`, as
// conserved_quantities decides it: walls, pins or outside forces push on it), or what it measures
// is m·θ' (a pendulum). "" when every change in the column is the engine's error.
std::string momentum_footnote(const SceneDescription& scene, bool momentum_conserved);

// Whether the load average exceeded the number of cores as the timing began or as it ended (the
// 1-minute average lags: either end may show a busy spell). False where the load or the cores are
// not known.
bool busy_machine(const MachineLoad& load);

// One sentence for the terminal and the report when busy_machine(load), else "": the timings were
// taken on a busy machine, and the ratios between engines may be off.
std::string busy_machine_warning(const MachineLoad& load);

// The report's sentence of the load ("The machine's 1-minute load average was 0.52 as the timing
// began and 0.61 as it ended, on 2 cores."; "The machine has 2 cores; its load average could not be
// read."); "" when neither the load nor the cores are known.
std::string machine_load_sentence(const MachineLoad& load);


// A vector as "(1, −0.5)" with three significant digits (the report's and the table's style).
std::string format_vector(const std::vector<double>& v);

}  // namespace motus::compare
