#include "motus/precision/motus_sweep.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "motus/exact/exact_solution.hpp"
#include "motus/precision/run_times.hpp"
#include "motus/scene_error.hpp"
#include "motus/simulation.hpp"

namespace motus::precision {

std::vector<double> fixed_steps(const SceneDescription& scene, const Sweep& sweep) {
  const bool land_on_end = last_reference_time(scene).has_value();
  const double span = sweep.end - scene.start_time;
  std::vector<double> steps;
  for (int k = 0; k < sweep.levels; ++k) {
    double h = sweep.dt / std::ldexp(1.0, k);
    if (land_on_end && span > 0) h = span / std::ceil(span / h - 1e-9);
    steps.push_back(h);
  }
  return steps;
}

std::vector<double> tolerances(const Sweep& sweep) {
  std::vector<double> tol;
  for (int j = 0; j <= 10 * sweep.per_decade; ++j) tol.push_back(std::pow(10.0, -3.0 - static_cast<double>(j) / sweep.per_decade));
  return tol;
}

double nominal_steps(const SceneDescription& scene, const Sweep& sweep, double h) {
  return static_cast<double>(fixed_step_count(sweep.end - scene.start_time, h));
}

std::vector<double> engine_steps() { return {1.0 / 30, 1.0 / 60, 1.0 / 120, 1.0 / 240, 1.0 / 480, 1.0 / 960}; }

Vector true_state(const SceneDescription& scene, double t) {
  const auto exact = exact_state(scene, t);
  if (!exact) throw std::invalid_argument(scene.name + ": no reference state at t = " + std::to_string(t));
  return *exact;
}

double state_error(const SceneDescription& scene, const Vector& y, double t) {
  const double error = (y - true_state(scene, t)).cwiseAbs().maxCoeff();
  return std::isfinite(error) ? error : INFINITY;
}

namespace {

// One run of the point (Sweep::round says which): its numbers, and its time from the first step to
// the last (run_times.hpp: the Simulation is built outside it).
Point measure(const SceneDescription& scene, const Method& method, double h, double tol, const Sweep& sweep) {
  Point p;
  p.h = h;
  p.tolerance = method.adaptive() ? tol : 0;
  Simulation sim(scene, method);
  Stopwatch watch;
  try {
    if (!sweep.timed() && sweep.now_and_then) {  // (the untimed run: a call per step costs it nothing that counts)
      long count = 0;
      sim.advance(sweep.end, h, Tolerance{tol, tol}, [&](const Simulation&) {
        if ((++count & 0xFFFF) == 0) sweep.now_and_then();
      });
    } else {
      watch.start();
      sim.advance(sweep.end, h, Tolerance{tol, tol});
      watch.stop();
    }
  } catch (const StepSizeUnderflow& e) {  // the tolerance cannot be met: no point here
    p.failed = e.what();
    return p;
  }
  p.t_end = sim.time();
  p.error = state_error(scene, sim.state(), sim.time());
  p.steps = sim.steps();
  p.evaluations = sim.evaluations();
  p.seconds = p.median_seconds = watch.seconds();
  return p;
}

}  // namespace

std::string why_motus_cannot_run(const SceneDescription& scene, const Method& method) {
  if (method.needs_mechanical() && !scene.is_mechanical()) {
    // (A plug-in's step(x, v) need not be symplectic: a student's explicit Euler steps bodies too.)
    return method.is_external() ? "steps bodies (x and v): needs a mechanical scene (bodies)"
                                : "symplectic: needs a mechanical scene (bodies)";
  }
  try {
    Simulation refused(scene, method);  // collisions or constraints the method cannot run
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

Curve sweep_motus(const SceneDescription& scene, const Method& method, const Sweep& sweep) {
  Curve c;
  c.method = method.name();
  c.engine = method.is_external() ? c.method.substr(0, c.method.find(':')) : "motus";
  c.description = method.description();
  c.adaptive = method.adaptive();
  c.unsupported = why_motus_cannot_run(scene, method);
  if (!c.unsupported.empty()) return c;
  if (c.adaptive) {
    for (double tol : tolerances(sweep)) {
      c.points.push_back(measure(scene, method, sweep.dt, tol, sweep));
      if (sweep.point_done) sweep.point_done(nominal_steps(scene, sweep, sweep.dt));
    }
  } else {
    for (const double h : fixed_steps(scene, sweep)) {
      c.points.push_back(measure(scene, method, h, 0, sweep));
      if (sweep.point_done) sweep.point_done(nominal_steps(scene, sweep, h));
    }
  }
  return c;
}

}  // namespace motus::precision
