#include "stress_measures.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "interrupt.hpp"
#include "motus/simulation.hpp"

namespace motus::cli::stress {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// |E − E0| relative to |E0| (to 1 when E0 = 0).
double relative(double e, double e0) { return std::abs(e - e0) / (e0 != 0 ? std::abs(e0) : 1.0); }

// The energy past which a bound motion is no longer bound: an orbit's 0 (E ≥ 0 escapes), and a
// pendulum's 2 m g/L, its potential at the top (in the units motus reports a pendulum's energy in,
// divided by L²): a swing whose energy passes it goes over the top. Without this, a pendulum's
// energy, whose potential is bounded, never reached 10⁶ |E0|: explicit Euler at ωh ≈ 48 (h = 15 s
// on a 2 s swing) was "stable" while it spun over the top (two audits).
double bound_energy(const SceneDescription& scene) {
  if (!scene.mechanical || scene.mechanical->forces.pendulums.empty()) return 0;
  double top = 0;
  for (const auto& p : scene.mechanical->forces.pendulums) top += 2 * scene.mechanical->bodies[static_cast<size_t>(p.body)].mass * p.g / p.length;
  return top;
}

// The blow-up rule of every stability, stiffness and drift run (docs/cli.md): the energy is not
// finite, or it changed by more than `factor` times |E0|, or a motion that was bound (E0 below
// `bound`, bound_energy's) is no longer (E ≥ bound): an orbit escaped, a pendulum went over the top.
std::string blow_up(double e, double e0, double factor, double bound) {
  if (!std::isfinite(e)) return "not finite";
  if (relative(e, e0) > factor) return "energy beyond the factor";
  if (e0 < bound && e >= bound) return bound == 0 ? "escaped (E >= 0)" : "over the top (E >= the pendulum's 2 m g/L)";
  return "";
}

// Runs up to `steps` steps of h from where `sim` is, calling `each` after every step, and stops
// at the end of the chunk in progress once `each` returns false (a blown-up state is then only
// stepped a little further and never looked at). Returns the steps that `each` saw; a run that
// fails (an exception: a state the engine refuses) ends it, with `failure` set.
long run_steps(Simulation& sim, long steps, double h, const std::function<bool(const Simulation&)>& each, const Tick& tick,
               std::string& failure) {
  constexpr long kChunk = 256;
  const long first = sim.steps();
  long seen = 0;
  bool go = true;
  try {
    for (long done = 0; go && done < steps;) {
      const long n = std::min(kChunk, steps - done);
      // n steps from where the clock is now: from t0, t0 + (done + n)·h and the clock (each chunk's
      // start plus its steps) part by a few roundings a chunk, and after 10^7 steps that made one
      // step more.
      sim.advance(sim.time() + static_cast<double>(n) * h, h, Tolerance{}, [&](const Simulation& s) {
        if (!go) return;
        ++seen;
        tick(static_cast<double>(seen) / static_cast<double>(steps));
        if (!each(s)) go = false;
      });
      const long before = done;
      done = sim.steps() - first;
      // A step that no longer moves the clock (times too coarse for h) would never end the run.
      if (done == before && go) throw std::runtime_error(fmt::format("the steps no longer advance the time at t = {:g}", sim.time()));
    }
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    failure = e.what();
  }
  return seen;
}

// A trial of `steps` steps of h: the largest energy error and whether it blew up.
StabilityTrial trial(const SceneDescription& scene, Integrator integrator, double h, const Settings& settings, const Tick& tick) {
  Simulation sim(scene, integrator);
  const double e0 = sim.energy()->total, bound = bound_energy(scene);
  StabilityTrial t{h, 0, false};
  std::string failure;
  run_steps(sim, settings.steps, h,
            [&](const Simulation& s) {
              const double e = s.energy()->total;
              t.max_error = std::max(t.max_error, std::isfinite(e) ? relative(e, e0) : kInf);
              if (!blow_up(e, e0, settings.energy_factor, bound).empty()) t.blown = true;
              return !t.blown;
            },
            tick, failure);
  if (!failure.empty()) t.blown = true, t.max_error = kInf;
  return t;
}

std::string format_g(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return text;
}

}  // namespace

StabilityTheory stability_theory(Integrator integrator, long steps, double factor) {
  // Euler's energy grows by 1 + z² a step and midpoint's by 1 + z⁴/4 (integrators.md): `steps` of them
  // pass 1 + factor where that per-step growth is (1 + factor)^(1/steps).
  const double growth = std::expm1(std::log1p(factor) / static_cast<double>(steps));
  const std::string run = fmt::format("{} steps pass the factor beyond ωh = ", steps);
  switch (integrator) {
    case Integrator::SymplecticEuler:
    case Integrator::SymplecticEulerX:
    case Integrator::Verlet:
    case Integrator::VelocityVerlet: return {2, true, false, "ωh < 2"};
    case Integrator::Rk4: return {2 * std::numbers::sqrt2, true, true, "ωh ≤ 2√2"};
    // Where the half trace of the product of its three Verlet step matrices (steps w₁h, w₀h, w₁h,
    // w₁ = 1/(2 − ∛2), w₀ = −∛2/(2 − ∛2)) first reaches −1, found by bisection: 1.5734019474345.
    case Integrator::Yoshida4: return {1.5734019474345, true, false, "ωh < 1.5734 (its step matrix)"};
    case Integrator::Euler: {
      const double z = std::sqrt(growth);
      return {z, false, true, "none: energy × (1 + (ωh)²) a step; " + run + fmt::format("{:.5g}", z)};
    }
    case Integrator::Midpoint: {
      const double z = std::sqrt(std::sqrt(4 * growth));
      return {z, false, true, "none: energy × (1 + (ωh)⁴/4) a step; " + run + fmt::format("{:.5g}", z)};
    }
    default: return {0, true, false, "adaptive: it chooses its own steps"};
  }
}

std::optional<double> harmonic_omega(const SceneDescription& scene) {
  if (scene.exact != "harmonic" || !scene.mechanical) return std::nullopt;
  const auto& m = *scene.mechanical;
  if (m.bodies.size() != 1 || m.forces.springs.size() != 1 || m.forces.springs[0].damping != 0) return std::nullopt;
  return std::sqrt(m.forces.springs[0].stiffness / m.bodies[0].mass);
}

StabilityResult measure_stability(const SceneDescription& scene, Integrator integrator, const Settings& settings,
                                  const Tick& tick) {
  StabilityResult r;
  r.integrator = integrator;
  r.theory = harmonic_omega(scene) ? stability_theory(integrator, settings.steps, settings.energy_factor)
                                    : StabilityTheory{0, true, false, "not known for this scene"};
  if (info(integrator).adaptive) {
    r.skipped = "adaptive: it chooses its own steps";
    r.theory = stability_theory(integrator, settings.steps, settings.energy_factor);
    return r;
  }
  // Grow h by doubling from dt/1024 until a trial blows up (or shrink it when the first does),
  // then bisect between the last stable step and the first that blew up.
  auto run = [&](double h) {
    r.trials.push_back(trial(scene, integrator, h, settings, tick));
    return !r.trials.back().blown;
  };
  double lo = 0, hi = 0;
  double h = scene.dt / 1024;
  if (run(h)) {
    lo = h;
    for (int i = 0; i < 30 && hi == 0; ++i) {
      h *= 2;
      (run(h) ? lo : hi) = h;
    }
  } else {
    hi = h;
    for (int i = 0; i < 30 && lo == 0; ++i) {
      h /= 2;
      (run(h) ? lo : hi) = h;
    }
  }
  if (lo > 0 && hi > 0)
    for (int i = 0; i < 24; ++i) {
      const double mid = 0.5 * (lo + hi);
      (run(mid) ? lo : hi) = mid;
    }
  r.limit = lo;
  r.first_blowup = hi;
  std::sort(r.trials.begin(), r.trials.end(), [](const auto& a, const auto& b) { return a.h < b.h; });
  return r;
}

DriftResult measure_drift(const SceneDescription& scene, Integrator integrator, const Settings& settings, const Tick& tick) {
  DriftResult r;
  r.integrator = integrator;
  if (info(integrator).adaptive) {
    r.skipped = "adaptive: it chooses its own steps";
    return r;
  }
  Simulation sim(scene, integrator);
  const double e0 = sim.energy()->total, bound = bound_energy(scene);
  const long n = settings.drift_steps;
  const long tenth = std::max(1L, n / 10), hundredth = std::max(1L, n / 100);
  long next_sample = 1;
  int sample_index = 0;
  double window = 0, last_tenth_largest_e = 0;  // (the largest |E| over the last tenth)
  double rounding = 0;                           // the rounding floor so far: see drift_rounding_scale
  std::string failure;
  run_steps(sim, n, scene.dt,
            [&](const Simulation& s) {
              const long step = s.steps();
              const Energy energy = *s.energy();
              const double e = energy.total;
              const double error = std::isfinite(e) ? relative(e, e0) : kInf;
              rounding += drift_rounding_scale(s, integrator, scene.dt);
              window = std::max(window, error);
              if (step <= hundredth) r.first_hundredth_max = std::max(r.first_hundredth_max, error);
              if (step > n - tenth) {
                r.last_tenth_max = std::max(r.last_tenth_max, error);
                r.last_tenth_max_abs = std::max(r.last_tenth_max_abs, std::isfinite(e) ? std::abs(e - e0) : kInf);
                r.energy_scale = std::max(r.energy_scale, std::abs(energy.kinetic) + std::abs(energy.potential));
                last_tenth_largest_e = std::max(last_tenth_largest_e, std::abs(e));
              }
              r.steps = step;
              const std::string why = blow_up(e, e0, kInf, bound);  // only not finite, or no longer bound
              if (step >= next_sample || !why.empty() || step == n) {
                r.samples.push_back({step, s.time(), error, window});
                window = 0;
                while (next_sample <= step) next_sample = std::max(next_sample + 1, std::lround(std::pow(10.0, ++sample_index / 20.0)));
              }
              if (!why.empty()) {
                r.blown = why + " at t = " + format_g(s.time()) + " s";  // (stress runs mechanical scenes: seconds)
                return false;
              }
              return true;
            },
            tick, failure);
  if (!failure.empty()) r.blown = "the run failed: " + failure;
  r.rounding_floor = rounding;
  if (!r.blown.empty()) {
    r.verdict = r.blown;
  } else if (r.last_tenth_max_abs <= r.rounding_floor) {
    // Judged against the energies' own scale first: what rounding alone can do is no drift, however
    // large against E0. (Free fall: verlet's 4 J, rk4's 6e-5 J after 1000 s, on |KE| + |PE| = 1e8 J,
    // were "grows ×1.6e8" and "×8e5" against E0 = 54.5 J; explicit Euler's 481 J, n·m g² h²/2, is
    // far above its floor, 3e-3 J, and still grows.)
    r.verdict = "rounding (|E - E0| at most " + format_g(r.energy_scale > 0 ? r.last_tenth_max_abs / r.energy_scale : 0) +
                " of |KE| + |PE|)";
  } else {
    const double growth =
        r.first_hundredth_max > 0 ? r.last_tenth_max / r.first_hundredth_max : (r.last_tenth_max > 0 ? kInf : 1);
    // An error that is already most of E0 in the first hundredth and stays there is not a bounded
    // wobble: the energy is gone (rk4 on the spring at ωh = 0.71 loses 80 % of it in the first
    // hundredth, and its error can grow no further than 1). A wobble comes back up to E0 and over.
    const bool lost = r.last_tenth_max >= 0.5 && last_tenth_largest_e < 0.5 * std::abs(e0);
    r.verdict = growth > 1.5 ? "grows ×" + format_g(growth)
                : lost       ? "lost its energy (|E| at most " + format_g(last_tenth_largest_e / std::abs(e0)) +
                             " |E0| in the last tenth)"
                             : "bounded";
  }
  return r;
}

double drift_rounding_scale(const Simulation& sim, Integrator integrator, double h) {
  constexpr double kRoundings = 4 * std::numeric_limits<double>::epsilon();
  const Energy e = *sim.energy();
  double scale = std::abs(e.kinetic) + std::abs(e.potential);
  if (integrator == Integrator::Verlet) {
    const auto& bodies = sim.scene().mechanical->bodies;
    const auto& y = sim.state();
    const Eigen::Index n = y.size() / 2;
    const int d = sim.scene().mechanical->dimensions;
    for (Eigen::Index k = 0; k < n && static_cast<size_t>(k / d) < bodies.size(); ++k)
      scale += bodies[static_cast<size_t>(k / d)].mass * std::abs(y[n + k]) * std::abs(y[k]) / h;
  }
  return kRoundings * (std::isfinite(scale) ? scale : 0);
}

std::string stiffness_knob(const SceneDescription& scene) {
  if (!scene.mechanical) return "";
  const auto& f = scene.mechanical->forces;
  if (!f.springs.empty()) return "every spring's stiffness k";
  if (!f.central_gravity.empty() || !f.mutual_gravity.empty())
    return "the gravitational parameter (μ, G), with the velocities × √factor so that orbits keep their shape";
  if (!f.pendulums.empty()) return "a pendulum's g, with the angular velocity × √factor";
  return "";
}

SceneDescription stiffened(const SceneDescription& scene, double factor) {
  SceneDescription s = scene;
  auto& m = *s.mechanical;
  auto& f = m.forces;
  if (!f.springs.empty()) {
    for (auto& spring : f.springs) spring.stiffness *= factor;
    return s;
  }
  for (auto& g : f.central_gravity) g.mu *= factor;
  for (auto& g : f.mutual_gravity) g.G *= factor;
  for (auto& p : f.pendulums) p.g *= factor;
  for (auto& b : m.bodies)
    for (double& v : b.velocity) v *= std::sqrt(factor);
  return s;
}

std::vector<double> stiffness_factors() {
  std::vector<double> f;
  for (int k = 0; k <= 8; ++k) f.push_back(std::pow(10.0, k));
  return f;
}

StiffnessResult measure_stiffness(const SceneDescription& scene, Integrator integrator, const Settings& settings,
                                  const Tick& tick) {
  StiffnessResult r;
  r.integrator = integrator;
  if (info(integrator).adaptive) {
    r.skipped = "adaptive: it chooses its own steps";
    return r;
  }
  for (double factor : stiffness_factors()) {
    const StabilityTrial t = trial(stiffened(scene, factor), integrator, scene.dt, settings, tick);
    r.runs.push_back({factor, t.max_error, t.blown});
    if (t.blown && r.first_failure == 0) r.first_failure = factor;
  }
  return r;
}

// ---------------------------------------------------------------------------------------------
// Balls.

namespace {

double kinetic(const Simulation& s) { return s.energy()->kinetic; }

// Calls close(a, b, squared distance, contact distance) for every pair of balls whose centres are
// within `reach` times their contact distance (sort and sweep along x).
template <class Close>
void for_each_close_pair(const Simulation& s, double reach, Close close) {
  const auto& m = *s.scene().mechanical;
  const int d = m.dimensions;
  const auto& x = s.state();
  std::vector<int> balls;
  double r_max = 0;
  for (size_t i = 0; i < m.bodies.size(); ++i)
    if (m.bodies[i].radius > 0) balls.push_back(static_cast<int>(i)), r_max = std::max(r_max, m.bodies[i].radius);
  std::sort(balls.begin(), balls.end(), [&](int a, int b) { return x[a * d] < x[b * d]; });
  for (size_t i = 0; i < balls.size(); ++i)
    for (size_t j = i + 1; j < balls.size() && x[balls[j] * d] - x[balls[i] * d] <= 2 * r_max * reach; ++j) {
      const int a = balls[i], b = balls[j];
      double d2 = 0;
      for (int k = 0; k < d; ++k) d2 += (x[a * d + k] - x[b * d + k]) * (x[a * d + k] - x[b * d + k]);
      const double contact = m.bodies[static_cast<size_t>(a)].radius + m.bodies[static_cast<size_t>(b)].radius;
      if (d2 <= contact * contact * reach * reach) close(a, b, d2, contact);
    }
}

// The deepest overlap of two balls, over their contact distance.
double deepest_overlap(const Simulation& s) {
  double deepest = 0;
  for_each_close_pair(s, 1, [&](int, int, double d2, double contact) {
    deepest = std::max(deepest, (contact - std::sqrt(d2)) / contact);
  });
  return deepest;
}

// The pairs of balls touching or overlapping now (within a relative 1e-9 of their contact
// distance: verlet's projection leaves a pair it parted at that distance, to rounding), sorted.
std::vector<std::pair<int, int>> touching_pairs(const Simulation& s) {
  std::vector<std::pair<int, int>> pairs;
  for_each_close_pair(s, 1 + 1e-9, [&](int a, int b, double, double) { pairs.emplace_back(std::min(a, b), std::max(a, b)); });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Bodies outside every box of the scene (by more than 1e-9 of the box's size).
long outside_boxes(const Simulation& s) {
  const auto& m = *s.scene().mechanical;
  if (m.colliders.boxes.empty()) return 0;
  const int d = m.dimensions;
  long outside = 0;
  for (size_t i = 0; i < m.bodies.size(); ++i) {
    const double r = m.bodies[i].radius;
    bool inside_one = false;
    for (const auto& box : m.colliders.boxes) {
      bool inside = true;
      for (int k = 0; k < d; ++k) {
        const double tol = 1e-9 * (box.max[static_cast<size_t>(k)] - box.min[static_cast<size_t>(k)]);
        const double x = s.state()[static_cast<Eigen::Index>(i) * d + k];
        inside = inside && x >= box.min[static_cast<size_t>(k)] + r - tol && x <= box.max[static_cast<size_t>(k)] - r + tol;
      }
      inside_one = inside_one || inside;
    }
    outside += !inside_one;
  }
  return outside;
}

double largest_radius(const MechanicalDescription& m) {
  double r = 0;
  for (const auto& b : m.bodies) r = std::max(r, b.radius);
  return r > 0 ? r : 0.5;
}

BodyDescription ball(int d, double mass, double r, double e, double x0, double x1, double v0) {
  BodyDescription b;
  b.mass = mass;
  b.position.assign(static_cast<size_t>(d), 0.0);
  b.velocity.assign(static_cast<size_t>(d), 0.0);
  b.position[0] = x0;
  if (d > 1) b.position[1] = x1;
  b.velocity[0] = v0;
  b.radius = r;
  b.restitution = e;
  return b;
}

SceneDescription bodies_only(const SceneDescription& like, Integrator integrator) {
  SceneDescription s;
  s.name = like.name;
  s.integrator = info(integrator).name;
  s.dt = like.dt;
  s.duration = like.dt;
  MechanicalDescription m;
  m.dimensions = like.mechanical->dimensions;
  m.constraint_iterations = like.mechanical->constraint_iterations;
  s.mechanical = m;
  return s;
}

}  // namespace

void ContactCount::start(const Simulation& sim) {
  if (integrator_ == Integrator::Verlet) touching_ = touching_pairs(sim);
}

void ContactCount::after_step(const Simulation& sim) {
  if (integrator_ != Integrator::Verlet) {
    count_ = sim.world() ? sim.world()->collision_counters().ball_collisions : 0;
    return;
  }
  auto now = touching_pairs(sim);
  std::vector<std::pair<int, int>> begun;
  std::set_difference(now.begin(), now.end(), touching_.begin(), touching_.end(), std::back_inserter(begun));
  count_ += static_cast<long>(begun.size());
  touching_ = std::move(now);
}

std::vector<double> mass_ratios() {
  std::vector<double> r;
  for (int k = 0; k <= 6; ++k) r.push_back(std::pow(10.0, k));
  return r;
}

MassRatioRow measure_mass_ratio(const SceneDescription& scene, Integrator integrator, double ratio, const Settings& settings,
                                bool with_scene, const Tick& tick) {
  MassRatioRow row;
  row.integrator = integrator;
  row.ratio = ratio;
  const auto& m0 = *scene.mechanical;
  const int d = m0.dimensions;
  const double r = largest_radius(m0), dt = scene.dt;

  // The pair: masses 1 and ratio meeting head-on at ±u, halfway through their third step. The
  // formula: the course's 1-D collision (course.md, section 9) with the scene's restitution e for
  // impulses; verlet's projected contacts are perfectly inelastic (e = 0).
  {
    const double u = 1, ma = 1, mb = ratio;
    const double e_scene = m0.bodies.empty() ? 1.0 : m0.bodies[0].restitution;
    const double e = integrator == Integrator::Verlet ? 0.0 : e_scene;
    SceneDescription s = bodies_only(scene, integrator);
    const double gap = r + 2.5 * u * dt;
    s.mechanical->bodies = {ball(d, ma, r, e_scene, -gap, 0, u), ball(d, mb, r, 1, gap, 0, -u)};
    try {
      Simulation sim(s, integrator);
      const double ke0 = kinetic(sim);
      ContactCount contacts(integrator);
      contacts.start(sim);
      std::string failure;
      run_steps(sim, 8, dt, [&](const Simulation& x) { return contacts.after_step(x), true; }, tick, failure);
      if (!failure.empty()) throw std::runtime_error(failure);
      const double va = ((ma - e * mb) * u + (1 + e) * mb * -u) / (ma + mb);
      const double vb = ((mb - e * ma) * -u + (1 + e) * ma * u) / (ma + mb);
      const Eigen::Index n = 2 * d;
      const double got_a = sim.state()[n + 0], got_b = sim.state()[n + d];
      row.pair.velocity_error = std::max(std::abs(got_a - va), std::abs(got_b - vb)) / u;
      const double ke_formula = 0.5 * ma * va * va + 0.5 * mb * vb * vb;
      row.pair.energy_error = std::abs(kinetic(sim) - ke_formula) / ke0;
      const double p0 = ma * u - mb * u, p = ma * got_a + mb * got_b;
      row.pair.momentum_error = std::abs(p - p0) / (ma * u + mb * u);
      row.pair.collisions = contacts.count();
    } catch (const Interrupted&) {
      throw;
    } catch (const std::exception& e) {
      row.pair.failed = e.what();
    }
  }

  // The scene itself, with every second body ratio times heavier, for --duration; when its balls
  // have not met by then, on until --duration after they first do, and never past the scene's
  // duration. (For 1 s, head_on's balls, which meet at t = 1.5 s, never met: every ratio read 0.)
  if (with_scene) {
    row.gas_measured = true;
    SceneDescription s = scene;
    for (size_t i = 1; i < s.mechanical->bodies.size(); i += 2) s.mechanical->bodies[i].mass *= ratio;
    try {
      Simulation sim(s, integrator);
      const double e0 = sim.energy()->total;
      const long least = std::max(1L, std::lround(std::min(settings.duration, scene.duration) / dt));
      const long most = std::max(least, std::lround(scene.duration / dt));
      long seen = 0, first_contact = 0;  // (the step after which the first contact was counted; 0: none yet)
      ContactCount contacts(integrator);
      contacts.start(sim);
      std::string failure;
      row.gas_steps = run_steps(sim, most, dt,
                                [&](const Simulation& x) {
                                  ++seen;
                                  row.gas_energy_error = std::max(row.gas_energy_error, relative(x.energy()->total, e0));
                                  contacts.after_step(x);
                                  row.gas_collisions = contacts.count();
                                  if (first_contact == 0 && row.gas_collisions > 0) first_contact = seen;
                                  if (seen < least || first_contact == 0) return true;
                                  return first_contact <= least ? false : seen < first_contact + least;
                                },
                                tick, failure);
      if (!failure.empty()) row.gas_failed = failure;
    } catch (const Interrupted&) {
      throw;
    } catch (const std::exception& e) {
      row.gas_failed = e.what();
    }
  }
  return row;
}

std::vector<double> speeds() { return {1, 10, 100, 1000, 10000}; }

SpeedRow measure_speed(const SceneDescription& scene, Integrator integrator, double radii_per_step, bool with_scene,
                       const Tick& tick) {
  SpeedRow row;
  row.integrator = integrator;
  row.radii_per_step = radii_per_step;
  const auto& m0 = *scene.mechanical;
  const int d = m0.dimensions;
  const double r = largest_radius(m0), dt = scene.dt;

  // The pair: in a box of 40 radii, a ball at 4 r from the left wall shot along the box's middle
  // line at a resting ball in its centre. Both move on that line only, so the moving ball can
  // never get past the other: if it is ever found beyond it, it went through it.
  {
    const double side = 40 * r, speed = radii_per_step * r / dt;
    SceneDescription s = bodies_only(scene, integrator);
    auto& m = *s.mechanical;
    m.bodies = {ball(d, 1, r, 1, 4 * r, side / 2, speed), ball(d, 1, r, 1, side / 2, side / 2, 0)};
    for (int k = 2; k < d; ++k) m.bodies[0].position[static_cast<size_t>(k)] = m.bodies[1].position[static_cast<size_t>(k)] = side / 2;
    BoxCollider box;
    box.min = {0, 0, 0};
    box.max = {side, d > 1 ? side : 0, d > 2 ? side : 0};
    m.colliders.boxes.push_back(box);
    try {
      Simulation sim(s, integrator);
      const double ke0 = kinetic(sim);
      const long steps = std::clamp(static_cast<long>(std::ceil(3 * 40 / radii_per_step)), 10L, 1000L);
      std::string failure;
      row.pair_steps = run_steps(sim, steps, dt,
                                 [&](const Simulation& x) {
                                   const auto& y = x.state();
                                   if (!(y[0] < y[d])) row.pair_order_kept = false;  // the centres changed places
                                   if (outside_boxes(x) > 0) row.pair_inside = false;
                                   row.pair_energy_error = std::max(row.pair_energy_error, std::abs(kinetic(x) - ke0) / ke0);
                                   return true;
                                 },
                                 tick, failure);
      if (!failure.empty()) row.pair_failed = failure;
      row.pair_ball_collisions = sim.world()->collision_counters().ball_collisions;
    } catch (const Interrupted&) {
      throw;
    } catch (const std::exception& e) {
      row.pair_failed = e.what();
    }
  }

  // The scene's balls, every velocity scaled so that the fastest ball moves radii_per_step radii
  // a step, for about three crossings of their container (at least 3 steps, at most 300). (Not
  // when no body moves: there is no speed to scale; the command lists that as not measured.)
  if (with_scene) {
    SceneDescription s = scene;
    auto& m = *s.mechanical;
    double fastest = 0;
    for (const auto& b : m.bodies) {
      double v2 = 0;
      for (double v : b.velocity) v2 += v * v;
      fastest = std::max(fastest, std::sqrt(v2));
    }
    if (fastest == 0) return row;
    row.gas_measured = true;
    const double scale = radii_per_step * r / dt / fastest;
    for (auto& b : m.bodies)
      for (double& v : b.velocity) v *= scale;
    double side = 40 * r;
    for (const auto& box : m.colliders.boxes) side = std::max(side, box.max[0] - box.min[0]);
    const long steps = std::clamp(static_cast<long>(std::ceil(3 * side / (radii_per_step * r))), 3L, 300L);
    try {
      Simulation sim(s, integrator);
      const double e0 = sim.energy()->total;
      std::string failure;
      row.gas_steps = run_steps(sim, steps, dt,
                                [&](const Simulation& x) {
                                  row.gas_outside = std::max(row.gas_outside, outside_boxes(x));
                                  row.gas_max_overlap = std::max(row.gas_max_overlap, deepest_overlap(x));
                                  row.gas_energy_error = std::max(row.gas_energy_error, relative(x.energy()->total, e0));
                                  return true;
                                },
                                tick, failure);
      if (!failure.empty()) row.gas_failed = failure;
      if (sim.world()) {
        const auto c = sim.world()->collision_counters();
        row.gas_collisions = c.ball_collisions + c.wall_collisions;
      }
    } catch (const Interrupted&) {
      throw;
    } catch (const std::exception& e) {
      row.gas_failed = e.what();
    }
  }
  return row;
}

// ---------------------------------------------------------------------------------------------
// Sticks.

std::vector<std::string> stick_variants() { return {"every second body", "the last body"}; }

std::vector<size_t> stick_variant_bodies(const SceneDescription& scene, const std::string& variant) {
  const size_t n = scene.mechanical->bodies.size();
  std::vector<size_t> heavier;
  if (variant == "the last body") {
    if (n > 0) heavier.push_back(n - 1);
  } else {
    for (size_t i = 1; i < n; i += 2) heavier.push_back(i);
  }
  return heavier;
}

std::string stick_variant_not_measured(const SceneDescription& scene, const std::string& variant,
                                       const std::vector<std::string>& earlier) {
  const auto& m = *scene.mechanical;
  std::vector<bool> pinned(m.bodies.size(), false);
  for (const auto& p : m.pins) pinned[static_cast<size_t>(p.body)] = true;
  // The free bodies a variant makes heavier: a pinned one's mass changes nothing (the projection
  // holds it as if infinitely heavy).
  auto heavier_free = [&](const std::string& v) {
    std::vector<bool> heavier(m.bodies.size(), false);
    for (size_t i : stick_variant_bodies(scene, v)) heavier[i] = !pinned[i];
    return heavier;
  };
  const auto heavier = heavier_free(variant);
  for (const auto& before : earlier)
    if (heavier_free(before) == heavier) return "the same free bodies made heavier as by \"" + before + "\"";
  const bool joins = std::any_of(m.sticks.begin(), m.sticks.end(), [&](const StickConstraint& s) {
    const auto a = static_cast<size_t>(s.a), b = static_cast<size_t>(s.b);
    return !pinned[a] && !pinned[b] && heavier[a] != heavier[b];
  });
  if (!joins)
    return "no stick joins masses 1 and R: every stick from a body it makes heavier ends at a pinned body (a pin "
           "holds its body as if infinitely heavy) or at one made as heavy";
  return "";
}

StickRow measure_sticks(const SceneDescription& scene, const std::string& variant, double ratio, const Settings& settings,
                        const Tick& tick) {
  StickRow row;
  row.variant = variant;
  row.ratio = ratio;
  SceneDescription s = scene;
  for (size_t i : stick_variant_bodies(scene, variant)) s.mechanical->bodies[i].mass *= ratio;
  try {
    Simulation sim(s, Integrator::Verlet);
    row.max_error = sim.constraint_error();
    const long steps = std::max(1L, std::lround(std::min(settings.duration, scene.duration) / scene.dt));
    std::string failure;
    row.steps = run_steps(sim, steps, scene.dt,
                          [&](const Simulation& x) {
                            const double e = x.constraint_error();
                            row.max_error = std::max(row.max_error, std::isfinite(e) ? e : kInf);
                            return std::isfinite(e);
                          },
                          tick, failure);
    if (!failure.empty()) row.failed = failure;
    row.final_error = sim.constraint_error();
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception& e) {
    row.failed = e.what();
  }
  return row;
}

}  // namespace motus::cli::stress
