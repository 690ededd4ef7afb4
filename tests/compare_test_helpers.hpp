#pragma once
// What the peer-engine tests (test_compare_box2d.cpp, test_compare_bullet.cpp) share:
// loading shipped scenes, building an engine through the Backend interface, stepping it,
// and the one-body scenes of tests/reference/peers.md. MOTUS_SCENES_DIR comes from
// tests/CMakeLists.txt.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "motus/compare/backends/backend.hpp"
#include "motus/simulation.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace motus_test {

using motus::BodyDescription;
using motus::Integrator;
using motus::MechanicalDescription;
using motus::SceneDescription;
using motus::compare::Backend;
using motus::compare::make_backend;
using motus::compare::Snapshot;
using motus::compare::Unsupported;

inline SceneDescription load(const std::string& name, const std::vector<std::string>& overrides = {}) {
  return motus::load_scene(MOTUS_SCENES_DIR "/" + name + ".json", overrides);
}

// The steps a scene's duration takes at its dt (as motus counts them).
inline long steps_of(const SceneDescription& scene) { return motus::fixed_step_count(scene.duration, scene.dt); }

inline std::unique_ptr<Backend> built(const std::string& engine, const SceneDescription& scene, double dt,
                                      Integrator integrator = Integrator::SymplecticEuler) {
  auto b = make_backend(engine);
  b->build(scene, integrator, dt);
  return b;
}

// What `engine` refuses to build of `scene`, as Unsupported lists it; empty when it builds it.
inline std::vector<std::string> refused(const std::string& engine, const SceneDescription& scene, Integrator integrator,
                                        double dt = 0.01) {
  try {
    make_backend(engine)->build(scene, integrator, dt);
  } catch (const Unsupported& e) {
    return e.elements();
  }
  return {};
}

inline Snapshot state(const Backend& b) {
  Snapshot s;
  b.read(s);
  return s;
}

inline Snapshot run(Backend& b, long steps) {
  for (long i = 0; i < steps; ++i) b.step();
  return state(b);
}

// One body of mass 2 (so that F/m is not F), radius 0.5, no walls, in as many dimensions
// as x has numbers, stepped at 60 Hz.
inline SceneDescription one_body(std::vector<double> x, std::vector<double> v) {
  SceneDescription scene;
  MechanicalDescription m;
  m.dimensions = static_cast<int>(x.size());
  BodyDescription body;
  body.mass = 2;
  body.radius = 0.5;
  body.position = std::move(x);
  body.velocity = std::move(v);
  m.bodies.push_back(body);
  scene.mechanical = m;
  scene.integrator = "symplectic-euler";
  scene.dt = 1.0 / 60;
  return scene;
}

// Two of one_body's balls (radius 0.5, mass 2) at x = ∓3 moving towards each other at ±speed.
inline SceneDescription two_balls_head_on(double speed) {
  SceneDescription pair = one_body({-3, 0}, {speed, 0});
  BodyDescription other = pair.mechanical->bodies[0];
  other.position = {3, 0};
  other.velocity = {-speed, 0};
  pair.mechanical->bodies.push_back(other);
  return pair;
}

// head_on (masses 1 and 3 at ±1 m/s, e = 1) along a line: the same scene as a 1-D one.
inline SceneDescription head_on_along_a_line() {
  SceneDescription scene = load("head_on");
  scene.mechanical->dimensions = 1;
  for (auto& b : scene.mechanical->bodies) {
    b.position.resize(1);
    b.velocity.resize(1);
  }
  return scene;
}

// peers.md's gravity, g = 10 m/s² downward (along −y).
inline const motus::UniformGravity kPeersGravity{{0, -10, 0}};

inline SceneDescription with_peers_gravity(SceneDescription scene) {
  scene.mechanical->forces.gravity.push_back(kPeersGravity);
  return scene;
}

// How far rounding alone can move motus's kinetic energy in `steps` steps of a 2-D gas of equal
// balls with e = 1, relative to it (both peers' gas tests bound motus's drift by it). A bounce off a box's wall flips one velocity component: exact. A
// collision of two balls moves their energy by at most some 24 roundings (u = 2⁻⁵³) of it — the
// closing speed, the impulse, the normal's length, the new velocities' components — and a pair
// holds at most f = 2·v_max²/Σv² of the gas's energy, v_max the fastest ball of the run. So
// COLLISIONS × 24u·f, and 2·N·u for the two sums (N balls) that make the energy before and after.
inline double motus_gas_rounding_bound(const SceneDescription& scene, long steps) {
  motus::Simulation sim(scene, Integrator::SymplecticEuler);  // (the motus backend's run)
  const auto& bodies = scene.mechanical->bodies;
  double sum_v2 = 0, fastest2 = 0;
  for (const auto& b : bodies) sum_v2 += b.velocity[0] * b.velocity[0] + b.velocity[1] * b.velocity[1];
  const double t0 = sim.time();
  for (long i = 1; i <= steps; ++i) {
    sim.advance(t0 + static_cast<double>(i) * scene.dt, scene.dt, {});  // (as the backend steps)
    const motus::Vector v = sim.state().tail(static_cast<Eigen::Index>(2 * bodies.size()));
    for (size_t j = 0; j < bodies.size(); ++j) fastest2 = std::max(fastest2, v[2 * j] * v[2 * j] + v[2 * j + 1] * v[2 * j + 1]);
  }
  const auto counted = sim.world()->collision_counters();
  const double u = 0x1p-53, f = 2 * fastest2 / sum_v2, n = static_cast<double>(bodies.size());
  const double bound = (24 * static_cast<double>(counted.ball_collisions) * f + 2 * n) * u;
  std::printf("  motus: %ld ball and %ld wall collisions in %ld steps, the fastest ball %.3f m/s (f = %.3f): bound %.2e\n",
              counted.ball_collisions, counted.wall_collisions, steps, std::sqrt(fastest2), f, bound);
  return bound;
}

}  // namespace motus_test
