// A SceneDescription built by hand, as a library user builds one (not read by the scene loader,
// which checks every field with its path): Simulation refuses what it would otherwise read out of
// bounds, with a SceneError naming the field as a scene file would (simulation.hpp promises it),
// and fills a catalog system's parameters left out with its defaults, as the loader does.
#include <gtest/gtest.h>

#include "motus/scene_error.hpp"
#include "motus/simulation.hpp"

namespace {

using namespace motus;

SceneDescription one_body(int dimensions) {
  SceneDescription scene;
  MechanicalDescription m;
  m.dimensions = dimensions;
  BodyDescription b;
  b.position.assign(static_cast<size_t>(dimensions), 1.0);
  b.velocity.assign(static_cast<size_t>(dimensions), 0.0);
  m.bodies.push_back(b);
  scene.mechanical = m;
  scene.dt = 0.1;
  scene.duration = 1;
  return scene;
}

std::string refused_field(const SceneDescription& scene) {
  try {
    Simulation simulation(scene, Integrator::SymplecticEuler);
  } catch (const SceneError& e) {
    return e.field();
  }
  return "(not refused)";
}

TEST(HandBuiltScenes, WhatWouldBeReadOutOfBoundsIsRefusedByItsField) {
  SceneDescription spring = one_body(1);
  Spring s;
  s.a = 5;  // (read as body 5 of 1: an invalid read, under valgrind)
  spring.mechanical->forces.springs.push_back(s);
  EXPECT_EQ(refused_field(spring), "forces.springs[0].a");  // (a ForceSet keeps no file's order: by kind)

  SceneDescription position = one_body(1);
  position.mechanical->bodies[0].position = {1, 2};
  EXPECT_EQ(refused_field(position), "bodies[0].position");

  SceneDescription velocity = one_body(2);
  velocity.mechanical->bodies[0].velocity.clear();
  EXPECT_EQ(refused_field(velocity), "bodies[0].velocity");

  SceneDescription mass = one_body(2);
  mass.mechanical->bodies[0].mass = 0;
  EXPECT_EQ(refused_field(mass), "bodies[0].mass");

  EXPECT_EQ(refused_field(one_body(2)), "(not refused)");
}

TEST(HandBuiltScenes, ACatalogSystemsMissingParametersTakeTheirDefaults) {
  SceneDescription scene;
  scene.first_order = FirstOrderDescription{};
  scene.first_order->type = "lorenz";
  scene.first_order->initial = {1, 1, 1};
  scene.dt = 0.01;
  scene.duration = 0.1;
  SceneDescription explicit_defaults = scene;  // Lorenz's σ = 10, ρ = 28, β = 8/3
  explicit_defaults.first_order->parameters = {{"sigma", 10}, {"rho", 28}, {"beta", 8.0 / 3}};
  Simulation left_out(scene, Integrator::Rk4), given(explicit_defaults, Integrator::Rk4);  // (a bare map::at threw)
  left_out.advance(0.1, 0.01, {});
  given.advance(0.1, 0.01, {});
  EXPECT_EQ(left_out.state(), given.state());

  scene.first_order->parameters = {{"zeta", 1}};
  try {
    Simulation s(scene, Integrator::Rk4);
    FAIL() << "an unknown parameter was taken";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.field(), "system.parameters.zeta");
  }
}

}  // namespace
