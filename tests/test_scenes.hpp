#pragma once
// Scene builders and small helpers shared by the test suites.
#include <cmath>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "motus/exact/exact_solution.hpp"
#include "motus/scene.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/system_catalog.hpp"

namespace motus_test {

// One body of mass m on a zero-length spring of stiffness k to the anchor 0, in 1-D:
// x'' = −(k/m) x. Exact solution "harmonic".
inline motus::SceneDescription spring(double mass, double stiffness, double x0, double v0) {
  motus::SceneDescription scene;
  scene.name = "spring";
  motus::MechanicalDescription m;
  m.dimensions = 1;
  m.bodies.push_back({mass, {x0}, {v0}});
  motus::Spring s;
  s.a = 0;
  s.b = -1;
  s.stiffness = stiffness;
  m.forces.springs.push_back(s);
  scene.mechanical = m;
  scene.exact = "harmonic";
  return scene;
}

// x'' = −ω² x with m = 1, k = ω², started at (x0, v0) = (1, 0) unless told otherwise.
inline motus::SceneDescription oscillator(double omega, double x0 = 1, double v0 = 0) {
  return spring(1, omega * omega, x0, v0);
}

// Kepler's problem of tests/reference/integrators.md: μ = 1, q0 = (0.4, 0), p0 = (0, 2); e = 0.6,
// H0 = −0.5, L0 = 0.8, period 2π.
inline motus::SceneDescription kepler() {
  motus::SceneDescription scene;
  scene.name = "kepler";
  motus::MechanicalDescription m;
  m.dimensions = 2;
  m.bodies.push_back({1, {0.4, 0}, {0, 2}});
  motus::CentralGravity g;
  g.mu = 1;
  m.forces.central_gravity.push_back(g);
  scene.mechanical = m;
  scene.exact = "kepler";
  return scene;
}
inline constexpr double kKeplerPeriod = 2 * std::numbers::pi;  // integrators.md
inline constexpr double kKeplerEnergy = -0.5;                  // integrators.md: H0 = −0.5

// A first-order system of the catalog with every parameter at its default, some
// overridden.
inline motus::SceneDescription first_order(const std::string& type, std::vector<double> initial,
                                           const std::map<std::string, double>& overrides = {},
                                           double start_time = 0) {
  motus::SceneDescription scene;
  scene.name = type;
  motus::FirstOrderDescription f;
  f.type = type;
  for (const auto& p : motus::find_first_order_system(type)->parameters) f.parameters[p.name] = p.default_value;
  for (const auto& [name, value] : overrides) f.parameters[name] = value;
  f.initial = std::move(initial);
  scene.first_order = f;
  scene.start_time = start_time;
  return scene;
}

inline double max_norm(const motus::Vector& a, const motus::Vector& b) { return (a - b).cwiseAbs().maxCoeff(); }

// Max-norm error of a simulation's state against the scene's exact solution at the
// simulation's current time.
inline double error_vs_exact(const motus::Simulation& sim) {
  return max_norm(sim.state(), *motus::exact_state(sim.scene(), sim.time()));
}

// Run `scene` with a fixed step h = end/n to `end` and return the max-norm error there.
inline double fixed_step_error(const motus::SceneDescription& scene, motus::Integrator integrator, double end,
                               long n) {
  motus::Simulation sim(scene, integrator);
  sim.advance(end, end / static_cast<double>(n), motus::Tolerance{});
  return error_vs_exact(sim);
}

}  // namespace motus_test
