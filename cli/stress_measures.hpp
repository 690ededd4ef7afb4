#pragma once
// The measurements of `motus stress` (docs/cli.md, "motus stress"): each takes the scene as it
// was loaded, builds the variants it needs (a step, a stiffness, a mass ratio, a speed) as new
// scene descriptions, runs them through motus::Simulation and returns plain numbers. The
// command (stress_command.cpp) chooses which apply; the page (stress_page.cpp) draws them.
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "motus/integrate/integrator_catalog.hpp"
#include "motus/scene.hpp"

namespace motus {
class Simulation;
}

namespace motus::cli::stress {

struct Settings {
  long steps = 10000;          // steps of one stability or stiffness trial
  long drift_steps = 100000;   // steps of the long run
  double energy_factor = 1e6;  // blown up: |E − E0| > energy_factor·|E0|
  double duration = 1;         // simulated seconds of a mass-ratio or sticks run (at most the scene's); a
                               // mass-ratio scene run whose balls have not met by then runs on until this
                               // long after they first do (at most the scene's duration)
};

// Called every step or so with how far the run under way is (0 to 1 of its steps): the progress bar,
// which is also where Ctrl-C is honoured. (Without the fraction the bar stood still through a long
// run: one drift run of 10⁶ steps is a unit of the bar, as is a stability trial of a few hundred.)
using Tick = std::function<void(double)>;

// ---- stability: the largest stable step ---------------------------------------------------
struct StabilityTrial {
  double h = 0;
  double max_error = 0;  // the largest |E − E0|/|E0| over the trial (inf when not finite)
  bool blown = false;
};
struct StabilityTheory {
  double z = 0;           // the limit of ω h; 0 when it is not known
  bool stable_below = true;  // false: unstable at every h, and z is where a run of the trial's steps first passes the factor
  bool limit_included = false;  // whether ωh = z itself is still stable (RK4's ≤ 2√2; a run at Euler's z just reaches the factor)
  std::string text;       // "ωh < 2", "none: ...", "not known for this scene"
};
struct StabilityResult {
  Integrator integrator{};
  std::string skipped;  // why it was not measured ("" when it was)
  std::vector<StabilityTrial> trials;  // every step tried, sorted by h
  double limit = 0;          // the largest h found stable (0: none)
  double first_blowup = 0;   // the smallest h found to blow up (0: none up to the largest tried)
  StabilityTheory theory;
};
// The theory of integrators.md for x'' = −ω²x. Explicit Euler and midpoint are unstable at every
// h; for them z is where `steps` steps first take the energy beyond (1 + factor) times its start.
StabilityTheory stability_theory(Integrator integrator, long steps, double factor);
// ω when the scene is an undamped harmonic oscillator (exact "harmonic", no damping), else none.
std::optional<double> harmonic_omega(const SceneDescription& scene);
StabilityResult measure_stability(const SceneDescription& scene, Integrator integrator, const Settings& settings,
                                  const Tick& tick);

// ---- drift: the energy error over a long run ---------------------------------------------
struct DriftSample {
  long step = 0;
  double t = 0;
  double error = 0;       // |E − E0|/|E0| after this step
  double window_max = 0;  // the largest since the previous sample
};
struct DriftResult {
  Integrator integrator{};
  std::string skipped;
  std::vector<DriftSample> samples;  // about 20 a decade of steps, log-spaced
  long steps = 0;                    // steps run (fewer than asked when it blew up)
  double first_hundredth_max = 0, last_tenth_max = 0;  // the largest error over the first 1 % and the last 10 % of the run
  std::string blown;                 // "" or "not finite at t = …", "escaped (E >= 0) at t = …"
  // The energies' own scale, |KE| + |PE|, largest over the last tenth, and the rounding floor: what
  // rounding the state each step can do to the energy, summed over the run (drift_rounding_scale).
  // A last tenth's |E − E0| within that floor is rounding, whatever E0: free fall's E0 is 54.5 J
  // while its KE and PE pass 5e7 J each, and |E − E0|/|E0| is then cancellation.
  double energy_scale = 0, rounding_floor = 0, last_tenth_max_abs = 0;
  std::string verdict;  // "rounding (…)", "bounded", "grows ×…", "lost its energy (…)", or the blow-up
};
// The energy change that rounding the state once can make, after one step: a few roundings (4 ε)
// of |KE| + |PE|; for verlet, which carries a velocity as the difference of two positions over h,
// also each coordinate's rounding ε|x| as a velocity error ε|x|/h, m|v|·4ε|x|/h.
double drift_rounding_scale(const Simulation& sim, Integrator integrator, double h);
DriftResult measure_drift(const SceneDescription& scene, Integrator integrator, const Settings& settings, const Tick& tick);

// ---- stiffness: the force constant raised by decades at a fixed dt ------------------------
struct StiffnessRun {
  double factor = 1;
  double max_error = 0;
  bool blown = false;
};
struct StiffnessResult {
  Integrator integrator{};
  std::string skipped;
  std::vector<StiffnessRun> runs;
  double first_failure = 0;  // the first factor that blew up (0: none)
};
// What is raised ("" when the scene has no such constant): every spring's k; or μ and G, with the
// velocities × √factor so that orbits keep their shape; or a pendulum's g.
std::string stiffness_knob(const SceneDescription& scene);
SceneDescription stiffened(const SceneDescription& scene, double factor);
std::vector<double> stiffness_factors();  // 1, 10, …, 10⁸
StiffnessResult measure_stiffness(const SceneDescription& scene, Integrator integrator, const Settings& settings,
                                  const Tick& tick);

// ---- mass ratio: collisions between balls of very different mass --------------------------
struct PairOutcome {
  double velocity_error = 0;  // max |v − v_formula| / u over both balls
  double energy_error = 0;    // |KE − KE_formula| / KE0
  double momentum_error = 0;  // |p − p0| / (m_a u + m_b u)
  long collisions = 0;        // ball–ball contacts (impulses, or contacts verlet's projection began)
  std::string failed;
};
struct MassRatioRow {
  Integrator integrator{};
  double ratio = 1;
  PairOutcome pair;          // a head-on pair of masses 1 and ratio, against the textbook formula
  // The scene with every second body's mass × ratio: max |E − E0|/|E0|, and its ball–ball contacts.
  // A run in which no balls met measured nothing: gas_collisions is then 0 and the page says so.
  bool gas_measured = false;  // false: not run (the scene has fewer than two balls)
  double gas_energy_error = 0;
  long gas_steps = 0;
  long gas_collisions = 0;
  std::string gas_failed;
};
std::vector<double> mass_ratios();  // 1, 10, …, 10⁶
// with_scene: also run the scene's own rows (it has two balls or more to meet).
MassRatioRow measure_mass_ratio(const SceneDescription& scene, Integrator integrator, double ratio,
                                const Settings& settings, bool with_scene, const Tick& tick);
// Ball–ball contacts after a step: an impulse's count (symplectic Euler's, from the engine's
// counters) or, for verlet, whose projection keeps no count, pairs that touch after a step and did
// not after the step before. Call after every step.
class ContactCount {
public:
  explicit ContactCount(Integrator integrator) : integrator_(integrator) {}
  void start(const Simulation& sim);  // the pairs touching at the start are not new contacts
  void after_step(const Simulation& sim);
  long count() const { return count_; }

private:
  Integrator integrator_;
  std::vector<std::pair<int, int>> touching_;
  long count_ = 0;
};

// ---- speed: balls that move many radii per step ------------------------------------------
struct SpeedRow {
  Integrator integrator{};
  double radii_per_step = 1;
  // A ball shot along a line at a resting ball in a box: they can never pass each other.
  long pair_steps = 0;
  bool pair_order_kept = true;   // the moving ball never got past the resting one
  bool pair_inside = true;       // both stayed in the box
  long pair_ball_collisions = 0;
  double pair_energy_error = 0;
  std::string pair_failed;
  // The scene's balls, their velocities scaled so that the fastest moves radii_per_step radii a step.
  long gas_steps = 0;
  long gas_outside = 0;          // balls found outside their container after a step
  double gas_max_overlap = 0;    // the deepest overlap of two balls after a step, / their contact distance
  double gas_energy_error = 0;
  long gas_collisions = 0;
  std::string gas_failed;
  bool gas_measured = false;     // false: not run (no body of the scene moves: no speed to scale)
};
std::vector<double> speeds();  // 1, 10, …, 10⁴ radii per step
SpeedRow measure_speed(const SceneDescription& scene, Integrator integrator, double radii_per_step, bool with_scene,
                       const Tick& tick);

// ---- sticks: sticks between masses of very different size ---------------------------------
struct StickRow {
  std::string variant;  // "every second body" or "the last body"
  double ratio = 1;
  double max_error = 0;    // the largest relative stick-length error over the run
  double final_error = 0;  // at its end
  long steps = 0;
  std::string failed;
};
std::vector<std::string> stick_variants();
// The bodies a variant makes R times heavier.
std::vector<size_t> stick_variant_bodies(const SceneDescription& scene, const std::string& variant);
// Why a variant measures nothing new ("" when it does): it makes the same free bodies heavier as a
// variant in `earlier`, or no stick joins a body it makes heavier to a free body it does not (a
// pinned end is as if infinitely heavy, whatever its mass).
std::string stick_variant_not_measured(const SceneDescription& scene, const std::string& variant,
                                       const std::vector<std::string>& earlier);StickRow measure_sticks(const SceneDescription& scene, const std::string& variant, double ratio, const Settings& settings,
                        const Tick& tick);

}  // namespace motus::cli::stress
