#pragma once
// Run one scene in several engines, in one process, with the same dt and duration,
// and measure them all with the same Metrics: the data behind `motus compare`.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "motus/compare/backends/backend.hpp"
#include "motus/compare/metrics.hpp"
#include "motus/compare/timing.hpp"

namespace motus::compare {

struct EngineRun {
  std::string engine, version;
  bool supported = true;
  std::vector<std::string> unsupported;  // "not supported by box2d: 3-D scenes", ...
  std::vector<std::string> settings, notes;
  std::vector<MetricsRow> rows;          // at t0 and every sample time
  std::vector<Snapshot> frames;          // at t0 and every frame_every steps (the pictures and the replay)
  std::vector<double> frame_energies;    // total energy of each frame
  Snapshot last;                         // the state at the end of the run
  long steps = 0;
  // CPU seconds of all `steps` step() calls, one number per timing round (timing.hpp).
  std::vector<double> round_seconds;

  // Summaries (meaningful when supported and rows is not empty).
  // `divisor`: energy_divisor's for this run (0: the changes in joules).
  double energy_drift(double divisor) const;      // (E_end − E_0)/divisor
  double max_energy_error(double divisor) const;  // max |E − E_0|/divisor over the samples
  double momentum_drift() const;     // |p_end − p_0| / momentum_scale()
  double momentum_scale() const;     // max(|p_0|, Σ m|v_0|), or 1 (changes in kg·m/s) when both are 0
  double max_penetration() const;    // m, over every step (penetration_every_step) and every sample
  double max_constraint_error() const;  // over every step (stick_error_every_step) and every sample after the start
  double start_constraint_error() const;  // the scene's own, at t = 0, before any engine has stepped
  double not_finite_from() const;    // the first sample's time whose state is not finite; NaN: none
  double max_from_motus() const;     // m
  double max_from_exact() const;     // m; −1 when the scene has no analytic solution
  // Microseconds per step over the timing rounds: min, median, max (0 without rounds).
  Timings microseconds_per_step() const;

  double scale_of_momentum = 0;  // Σ m|v_0|, set by run_comparison
  // The largest relative stick-length error over every step of the metrics run (a stick can
  // stretch most between two samples: motus run, bench_constraints and the peers' notes take it
  // every step too). 0 in a scene without sticks.
  double stick_error_every_step = 0;
  // The deepest overlap over every step of the metrics run (an engine that resolves a contact
  // after it happens overlaps for a step or two, between samples: Box2D's head_on read 0 at 200
  // samples, 1.6e-4 m at 400). 0 in a scene where nothing can overlap.
  double penetration_every_step = 0;
};

// Whether the energy columns are changes in joules rather than fractions of |E₀|: when the
// scene starts with E₀ = 0 exactly (a pendulum let go at rest from the height of its pivot)
// there is no fraction to take. Decided on motus's run (else the first that ran), so that
// every engine's column is in one unit.
bool energy_in_joules(const std::vector<EngineRun>& runs);
// What run r's energy changes are divided by in every column, figure and file: 0 when they are in
// joules (every engine's change itself, whatever its own start), else |E₀| of r's own start — or
// motus's, should r's be exactly 0 where motus's is not (a peer's start rounded to its floats).
double energy_divisor(const std::vector<EngineRun>& runs, const EngineRun& r);
// An energy change in the columns' unit: divided by energy_divisor's divisor, or itself when that is 0.
double in_energy_unit(double change, double divisor);
// |to − from| (from empty: |to|), computed without overflow: a momentum of 1e154 kg·m/s has a
// finite length though its square is past the largest double.
double length_of_change(const std::vector<double>& from, const std::vector<double>& to);
// Whether the momentum columns are changes in kg·m/s: the scene starts with nothing moving (p₀ = 0
// and Σ m|v₀| = 0), so there is no scale to divide by.
bool momentum_in_kg_m_s(const std::vector<EngineRun>& runs);

// A plug-in's column: motus's world with the plug-in's parts, and its integrator when it
// brings the one asked for.
struct PluginEngine {
  std::string name;     // the plug-in's name, as in `engines`
  std::string version;  // a line for the table and the report ("student plug-in, build/student.so")
  ExternalParts parts;
  std::optional<Method> method;  // else the run's
};

struct ComparisonOptions {
  std::vector<std::string> engines = {"motus", "box2d", "bullet"};
  Method method = Integrator::SymplecticEuler;  // motus's; the peers integrate their way
  std::optional<PluginEngine> plugin;
  double dt = 0.01;
  double duration = 1;
  long samples = 200;  // metric rows over the run (at most one per step)
  long frame_every = 0;  // keep the state every this many steps, and the last, for pictures (0: none)
  int repeats = 0;       // timing rounds; 0: auto_rounds (5, fewer for a long scene)
  // Called with true as the timing rounds begin and with false as they end, however they end
  // (the command line quiets a plug-in's prints there: they came once, with the metrics run).
  std::function<void(bool)> timing_rounds;
};

// First every engine runs the scene once with its metrics sampled (untimed): the rows, frames,
// settings and notes. Then `repeats` timing rounds: in each, every engine builds the scene
// afresh and runs all its steps with nothing else in between, timed as one block of CPU time;
// the engines take turns within a round (the round's first engine rotates), which spreads the
// machine's slow spells across the engines (it cannot make rounds of very different lengths meet
// the same load: compare reports the load average). With repeats 0 (the default) the first
// round's time decides how many there are (auto_rounds, timing.hpp: 5 for a small scene).
// progress(fraction of all engines' steps done) is called now and then.
std::vector<EngineRun> run_comparison(const SceneDescription& scene, const ComparisonOptions& options,
                                      const std::function<void(double)>& progress = {});

}  // namespace motus::compare
