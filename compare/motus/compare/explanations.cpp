#include "motus/compare/explanations.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "motus/exact/exact_solution.hpp"
#include "motus/simulation.hpp"

namespace motus::compare {
namespace {

// Two significant digits: enough to compare engines that differ by decades.
std::string number(double x) {
  if (x == 0) return "0";
  if (std::isnan(x)) return "not finite";  // (a run that blew up: not "-nan"; an infinity reads "inf")
  return fmt::format("{:.2g}", x);
}

std::string signed_number(double x) {
  if (x == 0) return "0";
  if (std::isnan(x)) return "not finite";
  return fmt::format("{:+.2g}", x);
}

double distance(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (size_t k = 0; k < a.size() && k < b.size(); ++k) s += (a[k] - b[k]) * (a[k] - b[k]);
  return std::sqrt(s);
}

double length(const std::vector<double>& a) { return distance(a, std::vector<double>(a.size(), 0.0)); }

std::vector<const EngineRun*> supported(const std::vector<EngineRun>& runs) {
  std::vector<const EngineRun*> out;
  for (const auto& r : runs)
    if (r.supported && !r.rows.empty()) out.push_back(&r);
  return out;
}

// "; bullet could not run it" for every engine that did not run.
std::string unsupported_tail(const std::vector<EngineRun>& runs) {
  std::string names;
  for (const auto& r : runs)
    if (!r.supported) names += (names.empty() ? "" : " and ") + r.engine;
  return names.empty() ? "" : "; " + names + " could not run it";
}

// "a, b and c"
// A stick's length against its bodies' start as written: lengths given to 7 digits differ by this
// much from the distance (a cloth's or rope's generated sticks are exact).
constexpr double kStickRounding = 1e-6;

std::string joined(const std::vector<std::string>& parts) {
  std::string out;
  for (size_t i = 0; i < parts.size(); ++i) out += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
  return out;
}

std::string solution_name(const SceneDescription& scene) {
  if (scene.exact == "free-flight") {
    const auto& m = *scene.mechanical;
    const bool collides = !m.colliders.empty() || std::count_if(m.bodies.begin(), m.bodies.end(),
                                                                [](const auto& b) { return b.radius > 0; }) > 1;
    if (collides) return "the free-flight solution (true collisions, event by event)";
    return m.forces.gravity.empty() ? "the exact straight line x₀ + v₀t" : "the exact parabola x₀ + v₀t + ½gt²";
  }
  if (scene.exact == "harmonic") return "the harmonic oscillator's closed form";
  if (scene.exact == "kepler") return "Kepler's orbit";
  if (scene.exact == "pendulum") return "the pendulum's elliptic-function solution";
  if (scene.exact == "projectile-drag") return "the projectile with linear drag, in closed form";
  return "the scene's reference states";
}

}  // namespace

bool conserves_energy(const SceneDescription& scene) {
  const auto& m = *scene.mechanical;
  for (const auto& b : m.bodies)
    if (b.restitution != 1) return false;
  for (const auto& p : m.colliders.planes)
    if (p.restitution != 1) return false;
  for (const auto& b : m.colliders.boxes)
    if (b.restitution != 1) return false;
  for (const auto& s : m.colliders.segments)
    if (s.restitution != 1) return false;
  for (const auto& s : m.forces.springs)
    if (s.damping != 0) return false;
  return m.forces.drag.empty();
}

std::string coordinate_unit(const SceneDescription& scene) {
  // (A pendulum's coordinate is its angle θ.)
  return scene.mechanical && !scene.mechanical->forces.pendulums.empty() ? "rad" : "m";
}

std::optional<double> end_past_duration(double start, double duration, double dt) {
  const double end = start + static_cast<double>(fixed_step_count(duration, dt)) * dt;
  if (fmt::format("{:g}", end) == fmt::format("{:g}", start + duration)) return std::nullopt;
  return end;
}

std::string momentum_quantity(const SceneDescription& scene) {
  return coordinate_unit(scene) == "rad" ? "m·θ'" : "momentum";
}

std::string momentum_footnote(const SceneDescription& scene, bool momentum_conserved) {
  if (momentum_quantity(scene) != "momentum")
    return "* This scene's coordinate is the pendulum's angle θ: that column is the change in m·θ' (the mass "
           "times the angular velocity), not in a momentum, and the pendulum's gravity changes it: it shows the "
           "swing, not an engine's error.";
  if (momentum_conserved) return "";
  return "* This scene does not keep its momentum (walls, pins or outside forces act on it): that column shows their "
         "push, not an engine's error.";
}

namespace {
// A load average as the timing's sentences give it: two decimals, or "not known".
std::string load_text(double x) { return std::isnan(x) ? std::string("not known") : fmt::format("{:.2f}", x); }
}  // namespace

bool busy_machine(const MachineLoad& load) {
  // (A load not known is NaN, which compares false: no warning.)
  const double cores = static_cast<double>(load.cores);
  return load.cores > 0 && (load.at_start > cores || load.at_end > cores);
}

std::string busy_machine_warning(const MachineLoad& load) {
  if (!busy_machine(load)) return "";
  return fmt::format("the timings were taken on a busy machine (a 1-minute load average of {} as they began and "
                     "{} as they ended, on {} core{}): rounds of very different lengths do not meet the same "
                     "load, so the ratios between engines may be off",
                     load_text(load.at_start), load_text(load.at_end), load.cores, load.cores == 1 ? "" : "s");
}

std::string machine_load_sentence(const MachineLoad& load) {
  const std::string cores = fmt::format("{} core{}", load.cores, load.cores == 1 ? "" : "s");
  if (std::isnan(load.at_start) && std::isnan(load.at_end))
    return load.cores > 0 ? "The machine has " + cores + "; its load average could not be read." : "";
  return fmt::format("The machine's 1-minute load average was {} as the timing began and {} as it ended, on {}.",
                     load_text(load.at_start), load_text(load.at_end),
                     load.cores > 0 ? cores : std::string("a number of cores not known"));
}

namespace {

// "ball 4" for a ball, "body 4" for a point mass.
std::string body_name(const SceneDescription& scene, int i) {
  return (scene.mechanical->bodies[static_cast<size_t>(i)].radius > 0 ? "ball " : "body ") + std::to_string(i);
}

// What the exact velocities say, briefly: "ball 4 leaves at (1, 0) m/s and the others rest".
std::string exact_outcome(const SceneDescription& scene, const ExactAnswer& a) {
  std::vector<int> moving;
  for (size_t i = 0; i < a.velocity.size(); ++i)
    if (length(a.velocity[i]) > 1e-12) moving.push_back(static_cast<int>(i));
  if (moving.size() == 1 && a.velocity.size() > 2 && a.bodies <= ExactAnswer::kShownBodies)
    return body_name(scene, moving[0]) + " leaves at " + format_vector(a.velocity[static_cast<size_t>(moving[0])]) +
           " m/s and the others rest";
  std::vector<std::string> parts;
  for (size_t i = 0; i < a.velocity.size() && i < 3; ++i)
    parts.push_back(body_name(scene, static_cast<int>(i)) + " at " + format_vector(a.velocity[i]) + " m/s");
  if (a.bodies > 3) parts.push_back("…");
  return joined(parts);
}

}  // namespace

std::string format_vector(const std::vector<double>& v) {
  std::string out = "(";
  for (size_t k = 0; k < v.size(); ++k) {
    const double x = std::abs(v[k]) < 5e-13 ? 0.0 : v[k];  // rounding noise reads as 0
    // (fmt writes a NaN as "-nan" or "nan": a run that blew up says so in words)
    if (k) out += ", ";
    out += std::isnan(x) ? std::string("not a number") : fmt::format("{:.3g}", x);
  }
  return out + ")";
}

std::vector<ColumnDefinition> column_definitions(const SceneDescription& scene, long samples, bool momentum_conserved,
                                                 bool energy_in_joules, const InitialOverlap& overlap) {
  std::vector<ColumnDefinition> d;
  // (run_comparison's samples: at the steps nearest k·steps/samples, k = 1 … samples, the last at the end.)
  const std::string over = fmt::format("over the run's start and its {} samples (evenly spaced, the last at its end)",
                                       samples);
  const std::string energy = " E is the kinetic energy ½ m v² plus the potential energy of the scene's forces, computed "
                             "by the same code from every engine's positions and velocities.";
  if (energy_in_joules) {
    d.push_back({"energy drift [J]", "E_end − E₀: the total energy at the end against the start, in joules (+ gained, − "
                                     "lost). This scene starts with E₀ = 0, so there is no fraction of it to take." +
                                         energy});
    d.push_back({"max |ΔE| [J]", "the largest |E(t) − E₀| " + over + ", in joules: an engine can end near E₀ and stray on the way."});
  } else {
    d.push_back({"energy drift",
                 "(E_end − E₀) / |E₀|: the total energy at the end against the start, as a fraction (+ gained, − lost)." +
                     energy});
    d.push_back({"max |ΔE|/E₀", "the largest |E(t) − E₀| / |E₀| " + over + ": an engine can end near E₀ and stray on the way."});
  }
  if (momentum_quantity(scene) != "momentum")
    d.push_back({"m·θ' drift",
                 "|p_end − p₀| / scale, computed as the momentum drift of other scenes is, from p = Σ m v: this scene's "
                 "coordinate is the pendulum's angle θ, so p is Σ m·θ', the mass times the angular velocity, not a "
                 "momentum. The scale is the larger of |p₀| and Σ m |v₀|; a pendulum that starts at rest has none, "
                 "and the column is then |p_end − p₀| in kg·rad/s (the summary's momentum_unit says which). The "
                 "pendulum's gravity changes it: the column shows the swing, not an error."});
  else
    d.push_back({"momentum drift",
                 "|p_end − p₀| / scale, where p = Σ m v is the total momentum and the scale is the larger of |p₀| and "
                 "Σ m |v₀| (the momentum in play: in a head-on collision p₀ is 0, and dividing by it would mean "
                 "nothing); a scene that starts with nothing moving has no scale, and the column is then |p_end − p₀| "
                 "in kg·m/s (the summary's momentum_unit says which). " +
                     std::string(momentum_conserved
                                     ? "This scene keeps its momentum exactly (no walls, no outside force), so any "
                                       "change is the engine's error."
                                     : "This scene does not keep its momentum (walls, pins or outside forces push on "
                                       "it): the column shows that push, not an error.")});
  // (The scene's own overlap, moved apart before the first step: every engine's column starts with it.)
  const std::string start = initial_overlap_note(overlap, false);
  d.push_back({"max penetration [m]",
               "the deepest overlap of two balls (r_a + r_b − distance) or of a ball and a wall (radius − height above it) "
               "over every step of the run (an overlap lasts a step or two, between samples). " +
                   (start.empty()
                        ? std::string("Exact collisions never overlap; engines that resolve contacts after they happen do.")
                        : "This scene starts overlapping (" + start +
                              "), so every engine's column counts at least that start; past it, exact collisions never "
                              "overlap, and engines that resolve contacts after they happen do.")});
  d.push_back({"constraint error",
               scene.mechanical->sticks.empty()
                   ? "the largest |length − rest length| / rest length of a stick; this scene has no sticks (0)."
                   : "the largest |length − rest length| / rest length of any stick over every step of the run from "
                     "the first on (a stick stretches most between samples), as motus run measures it; the start is "
                     "the scene's, not an engine's, and is left out."});
  const std::string unit = coordinate_unit(scene);
  d.push_back({fmt::format("max distance from motus [{}]", unit),
               "the farthest any body gets from where motus has it at the same time, " + over +
                   ": where two engines part ways, not which is right."});
  if (has_exact_solution(scene))
    d.push_back({fmt::format("max distance from exact [{}]", unit),
                 "the same against the exact answer, " + solution_name(scene) + ": the engine's error itself."});
  d.push_back({"µs per step (min)",
               "CPU time spent inside the engine's steps, divided by the number of steps, in the fastest of the timing "
               "rounds: every engine runs the whole scene again in each round, with nothing measured in between, the "
               "engines taking turns (the first of them changing from round to round), which spreads the machine's "
               "slow spells across the engines; the run least disturbed is the one shown. Taking turns cannot make "
               "rounds of very different lengths meet the same load: on a busy machine (a load average above its "
               "cores, which the report gives) the ratios between engines may be off."});
  d.push_back({"median", "the median round's µs per step: how typical the fastest was."});
  d.push_back({"spread", "(slowest round − fastest round) / fastest round: how much the rounds disagreed."});
  d.push_back({"time / motus", "µs per step (min) divided by motus's: below 1 is faster than motus."});
  return d;
}

std::optional<ExactAnswer> exact_answer(const SceneDescription& scene, const std::vector<EngineRun>& runs) {
  if (!scene.mechanical || !has_exact_solution(scene)) return std::nullopt;
  const auto engines = supported(runs);
  if (engines.empty()) return std::nullopt;
  const double t = engines.front()->last.t;
  const auto y = exact_state(scene, t);
  if (!y) return std::nullopt;
  ExactAnswer a;
  a.t = t;
  a.source = solution_name(scene);
  a.dimensions = scene.mechanical->dimensions;
  a.bodies = static_cast<long>(scene.mechanical->bodies.size());
  const int d = a.dimensions;
  const Eigen::Index n = y->size() / 2;
  auto body = [&](const double* data, int i) { return std::vector<double>(data + i * d, data + (i + 1) * d); };
  const int shown = static_cast<int>(std::min<long>(a.bodies, ExactAnswer::kShownBodies));
  for (int i = 0; i < shown; ++i) {
    a.position.push_back(body(y->data(), i));
    a.velocity.push_back(body(y->data() + n, i));
  }
  for (const EngineRun* r : engines) {
    ExactAnswer::Engine e;
    e.engine = r->engine;
    // Each engine against the exact state at its own end: motus adds its steps up (t = 3.9999…96),
    // a peer may count them (t = 4), and the table's distance from exact is taken so too.
    const auto own = exact_state(scene, r->last.t);
    if (!own) continue;
    for (int i = 0; i < static_cast<int>(a.bodies); ++i) {
      const auto v = body(r->last.v.data(), i), x = body(r->last.x.data(), i);
      // (A run that blew up is infinitely far: NaN would lose every comparison and read as 0.)
      auto far = [](double d) { return std::isnan(d) ? INFINITY : d; };
      const double dv = far(distance(v, body(own->data() + n, i))), dx = far(distance(x, body(own->data(), i)));
      if (dv > e.worst_speed_error) e.worst_speed_error = dv, e.worst_body = i;
      e.worst_position_error = std::max(e.worst_position_error, dx);
      if (i < shown) e.velocity.push_back(v);
    }
    a.engines.push_back(std::move(e));
  }
  return a;
}

std::string what_to_notice(const SceneDescription& scene, const std::vector<EngineRun>& runs,
                           const std::optional<ExactAnswer>& exact) {
  const auto engines = supported(runs);
  if (engines.empty()) return "No engine could run this scene" + unsupported_tail(runs) + ".";
  const auto& m = *scene.mechanical;
  const bool collides = !m.colliders.empty() ||
                        std::count_if(m.bodies.begin(), m.bodies.end(), [](const auto& b) { return b.radius > 0; }) > 1;

  // Collisions with an exact outcome: how far each engine ended from the exact velocities.
  if (exact && scene.exact == "free-flight" && collides) {
    std::vector<std::string> parts;
    for (const auto& e : exact->engines) {
      if (e.worst_speed_error < 1e-9) {
        // The right velocities can still come with the wrong positions (a contact found a step late).
        if (e.worst_position_error > 1e-6)
          parts.push_back(e.engine + " has its velocities but ends " + number(e.worst_position_error) +
                          " m from its positions");
        else
          parts.push_back(e.engine + " ends on it (within " + number(e.worst_position_error) + " m and " +
                          number(e.worst_speed_error) + " m/s)");
        continue;
      }
      std::string part = e.engine + " is up to " + number(e.worst_speed_error) + " m/s off";
      if (e.worst_body < static_cast<int>(exact->velocity.size()))
        part += " (" + body_name(scene, e.worst_body) + " at " +
                format_vector(e.velocity[static_cast<size_t>(e.worst_body)]) + " m/s where the exact answer has " +
                format_vector(exact->velocity[static_cast<size_t>(e.worst_body)]) + ")";
      parts.push_back(part);
    }
    return fmt::format("The exact answer at t = {:g} s: {}; {}{}.", exact->t, exact_outcome(scene, *exact), joined(parts),
                       unsupported_tail(runs));
  }
  // Any other exact answer: the largest distance from it over the run.
  if (has_exact_solution(scene)) {
    // (A pendulum's coordinate is its angle θ: the distance is in radians.)
    const std::string unit = coordinate_unit(scene);
    std::vector<std::string> parts;
    for (const EngineRun* r : engines) {
      if (r->max_from_exact() < 0) continue;
      // (A run that blew up is not "inf m" away: say where its state stopped being finite.)
      if (!std::isnan(r->not_finite_from()))
        parts.push_back(fmt::format("{} not finite from t = {:g} s on", r->engine, r->not_finite_from()));
      else
        parts.push_back(fmt::format("{} {} {}", r->engine, number(r->max_from_exact()), unit));
    }
    if (!parts.empty())
      return "Against " + solution_name(scene) + ", the farthest each engine strays over the run: " + joined(parts) +
             unsupported_tail(runs) + ".";
  }
  // Sticks: their lengths should not change. And what each engine's way of keeping them costs in
  // energy (stick_pendulum: motus's projection loses 8.8 J of its 9.8, where Box2D loses 5.2 and
  // Bullet 1.0; the sentence ranked the lengths alone, an audit).
  if (!m.sticks.empty()) {
    std::vector<std::string> parts, energies;
    for (const EngineRun* r : engines) {
      parts.push_back(r->engine + " " + number(r->max_constraint_error()));
      energies.push_back(r->engine + " " + signed_number(r->energy_drift(energy_divisor(runs, *r))));
    }
    // (A scene whose sticks start off their lengths: said, and left out of every engine's figure.)
    const double start = engines.empty() ? 0 : engines.front()->start_constraint_error();
    const std::string start_note =
        start > kStickRounding ? "; the scene starts with them off by up to " + number(start) +
                                     " (its own lengths against its positions, not counted)"
                               : "";
    return "The sticks should keep their lengths" + start_note + "; the worst relative length error over the run: " + joined(parts) +
           unsupported_tail(runs) + ". Keeping them costs energy, each engine its own way (a projection or a solver "
           "that removes the velocity along a stick removes its energy); the energy change " +
           (energy_in_joules(runs) ? "in J (the scene starts with E₀ = 0): " : "relative to E₀: ") + joined(energies) + ".";
  }
  std::vector<std::string> parts;
  for (const EngineRun* r : engines) {
    const double divisor = energy_divisor(runs, *r);
    parts.push_back(r->engine + " " + signed_number(r->energy_drift(divisor)) + " (at worst " +
                    number(r->max_energy_error(divisor)) + ")");
  }
  const std::string measure = energy_in_joules(runs) ? "in J (the scene starts with E₀ = 0): " : "relative to E₀: ";
  if (conserves_energy(scene))
    return "The scene keeps its energy exactly, so every change is the engine's error; " + measure + joined(parts) +
           unsupported_tail(runs) + ".";
  return "The scene loses energy by design (restitution below 1, damping or drag), so compare the engines with each "
         "other; energy change " +
         measure + joined(parts) + unsupported_tail(runs) + ".";
}

}  // namespace motus::compare
