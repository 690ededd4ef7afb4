#pragma once
// What the peer-engine tests (test_compare_box2d.cpp, test_compare_bullet.cpp) share:
// loading shipped scenes, building an engine through the Backend interface, stepping it,
// and the one-body scenes of tests/reference/peers.md. MOTUS_SCENES_DIR comes from
// tests/CMakeLists.txt.
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

}  // namespace motus_test
