// Box2D 2.4.1 behind the backend interface (issue 4). Both engines run through
// Backend (make_backend("motus"), make_backend("box2d")) with the same dt.
//  - Without contacts, Box2D integrates as symplectic Euler does (tests/reference/
//    peers.md, docs/peers.md: v += h(g + F/m), then x += h v), so motus with symplectic-euler must
//    reproduce it to float precision.
//  - With contacts, Box2D's sequential-impulse solver differs from motus's exact
//    impulses at the time of impact: its deviations are measured here and asserted in a
//    band around today's value (the issue: "each peer's deviation ... asserted within
//    what it measures today"), so that a change is noticed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <unistd.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "motus/compare/backends/backend.hpp"
#include "compare_test_helpers.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace {

using namespace motus_test;

// Runs motus (symplectic Euler) and Box2D side by side and checks after every step that
// they agree to float precision: 1e-5 relative to the largest |coordinate| (|velocity|)
// seen so far. Float positions are rounded relative to their own size, and the rounding
// of each step's x += h·v accumulates along the path, so "relative" means relative to
// the path's scale, not to a coordinate that happens to pass near zero.
void expect_same_trajectory(const SceneDescription& scene, double dt, long steps) {
  auto motus = built("motus", scene, dt);
  auto box2d = built("box2d", scene, dt);
  Snapshot a, b;
  double x_scale = 1, v_scale = 1;
  for (long i = 1; i <= steps; ++i) {
    motus->step();
    box2d->step();
    motus->read(a);
    box2d->read(b);
    ASSERT_EQ(a.x.size(), b.x.size());
    EXPECT_NEAR(a.t, b.t, 1e-12);
    for (size_t k = 0; k < a.x.size(); ++k) {
      x_scale = std::max(x_scale, std::abs(a.x[k]));
      v_scale = std::max(v_scale, std::abs(a.v[k]));
    }
    for (size_t k = 0; k < a.x.size(); ++k) {
      ASSERT_NEAR(b.x[k], a.x[k], 1e-5 * x_scale) << "step " << i << ", coordinate " << k;
      ASSERT_NEAR(b.v[k], a.v[k], 1e-5 * v_scale) << "step " << i << ", coordinate " << k;
    }
  }
}

double kinetic_energy(const SceneDescription& scene, const Snapshot& s) {
  const auto& bodies = scene.mechanical->bodies;
  double e = 0;
  for (size_t i = 0; i < bodies.size(); ++i)
    e += 0.5 * bodies[i].mass * (s.v[2 * i] * s.v[2 * i] + s.v[2 * i + 1] * s.v[2 * i + 1]);
  return e;
}

double momentum(const SceneDescription& scene, const Snapshot& s, int k) {
  const auto& bodies = scene.mechanical->bodies;
  double p = 0;
  for (size_t i = 0; i < bodies.size(); ++i) p += bodies[i].mass * s.v[2 * i + static_cast<size_t>(k)];
  return p;
}

bool has_line_containing(const std::vector<std::string>& lines, const std::string& text) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

// ---- the same integrator: no contacts

TEST(Box2dSameIntegrator, FreeFallEndsWherePeersMdSays) {
  // peers.md: falling 1 s at 60 Hz from 100 m with g = 10 ends at y = 94.91667 m,
  // v = −10 m/s in motus's symplectic Euler, Box2D and Bullet (the exact fall: 95 m).
  const SceneDescription scene = with_peers_gravity(one_body({0, 100}, {0, 0}));
  const Snapshot b = run(*built("box2d", scene, 1.0 / 60), 60);
  EXPECT_NEAR(b.x[1], 94.91667, 1e-5 * 100);  // float: 1e-5 relative
  EXPECT_NEAR(b.v[1], -10, 1e-5 * 10);
  EXPECT_EQ(b.x[0], 0);
  EXPECT_NEAR(b.t, 1, 1e-12);
  expect_same_trajectory(scene, 1.0 / 60, 60);
}

TEST(Box2dSameIntegrator, ProjectileMatchesMotusToFloatPrecision) {
  // Launched at (20, 20) m/s under g = (0, −10): 4 s at 60 Hz (it lands near y = 0).
  expect_same_trajectory(with_peers_gravity(one_body({0, 0}, {20, 20})), 1.0 / 60, 240);
}

TEST(Box2dSameIntegrator, SpringAppliedAsAForceMatchesMotusToFloatPrecision) {
  // A zero-length spring (k = 4 N/m) from the body (m = 2 kg) to the origin: a 2-D
  // harmonic oscillator of period 2π·sqrt(m/k) ≈ 4.44 s, run for 10 s (600 steps). Box2D
  // gets F = −k x from PeerForces through ApplyForceToCenter before each step: its kick
  // is symplectic Euler's with the same force.
  SceneDescription scene = one_body({1, 0.5}, {0, 1});
  motus::Spring spring;
  spring.a = 0;
  spring.anchor = {0, 0, 0};
  spring.stiffness = 4;
  scene.mechanical->forces.springs.push_back(spring);
  expect_same_trajectory(scene, 1.0 / 60, 600);
}

TEST(Box2dSameIntegrator, OneDimensionalScenesRunOnTheXAxis) {
  // A 1-D scene is Box2D's x axis (y = 0, forces along x): the course's 1-D scenes are then
  // symplectic Euler with the same forces, to float precision — the spring (m = 10, k = 5,
  // x0 = 20) at h = 0.1 for 20 s, the oscillator, the damped spring, and the pendulum, whose
  // one coordinate is the angle (the pendulum law applied as a force on it).
  expect_same_trajectory(load("spring"), 0.1, 200);
  for (const char* name : {"oscillator", "damped_spring", "pendulum"}) {
    SCOPED_TRACE(name);
    const SceneDescription scene = load(name);
    expect_same_trajectory(scene, scene.dt, std::min(steps_of(scene), 2000L));
  }
  // A throw along x under g = −10 m/s² along it.
  SceneDescription throw1 = one_body({0}, {4});
  throw1.mechanical->forces.gravity.push_back({{-10, 0, 0}});
  expect_same_trajectory(throw1, 1.0 / 60, 120);
  EXPECT_TRUE(has_line_containing(built("box2d", throw1, 1.0 / 60)->settings(), "1-D: the x axis"));
  // The pendulum's coordinate is its angle: the notes' lengths are radians.
  auto pendulum = built("box2d", load("pendulum"), 0.01);
  run(*pendulum, 100);
  EXPECT_TRUE(has_line_containing(pendulum->notes(), "rad from the origin, the farthest a body came"));
  EXPECT_TRUE(has_line_containing(pendulum->notes(), "(2 rad per step; the fastest body moved"));
}

TEST(Box2dContacts, OneDimensionalCollisionsStayOnTheAxis) {
  // head_on along a line (masses 1 and 3 at ±1 m/s, e = 1): the same exact velocities as in
  // the plane, −2 and 0 m/s (contact normals along x: nothing leaves the axis).
  const SceneDescription line = head_on_along_a_line();
  const Snapshot s = run(*built("box2d", line, line.dt), steps_of(line));
  ASSERT_EQ(s.v.size(), 2u);
  EXPECT_NEAR(s.v[0], -2, 1e-6);
  EXPECT_NEAR(s.v[1], 0, 1e-6);
  // A ball between the ends of a 1-D box [0, 10] at 3 m/s, e = 1: it bounces between them,
  // keeping its speed, and never leaves the box (10 s at 60 Hz: three crossings).
  SceneDescription boxed = one_body({5}, {3});
  motus::BoxCollider box;
  box.min = {0, 0, 0};
  box.max = {10, 0, 0};
  boxed.mechanical->colliders.boxes.push_back(box);
  auto box2d = built("box2d", boxed, 1.0 / 60);
  for (int i = 0; i < 600; ++i) {
    box2d->step();
    const Snapshot b = state(*box2d);
    ASSERT_GE(b.x[0], 0.5 - 0.005) << "step " << i;  // (b2_linearSlop of overlap at most)
    ASSERT_LE(b.x[0], 9.5 + 0.005) << "step " << i;
    ASSERT_NEAR(std::abs(b.v[0]), 3, 1e-5) << "step " << i;
  }
}

TEST(Box2dSameIntegrator, PointsPassThroughEachOtherAndBounceOffWalls) {
  // Two points (radius 0) inside a box: as in motus, they meet the walls but not each
  // other (Box2D: a collision filter). Head-on at ±1 m/s from x = ∓1: they cross at
  // t = 1 s and reach the walls at x = ±5 at t = 6 s; 8 s is 480 steps.
  SceneDescription scene;
  MechanicalDescription m;
  m.dimensions = 2;
  BodyDescription a, b;
  a.position = {-1, 1};
  a.velocity = {1, 0};
  b.position = {1, 1};
  b.velocity = {-1, 0};
  m.bodies = {a, b};
  m.colliders.boxes.push_back({{-5, 0, 0}, {5, 10, 0}, 1});
  scene.mechanical = m;
  const Snapshot s = run(*built("box2d", scene, 1.0 / 60), 120);  // t = 2 s: crossed, not yet at a wall
  EXPECT_NEAR(s.x[0], 1, 1e-5);
  EXPECT_NEAR(s.x[2], -1, 1e-5);
  EXPECT_NEAR(s.v[0], 1, 1e-6);
  // After the walls (t = 8 s): body 0 bounced off x = 5 at t = 6 s and is back at 3 m. At 1/60 s
  // the points reach the walls at the end of step 360, exactly, so Box2D finds the contact at the
  // start of the next step as motus meets the wall at its end: no step late, no overlap to push
  // apart. What is left is float: each step's x += h·v rounds x to float, at most half an ulp of
  // |x| (2⁻²² m at 5 m), so over the path the positions part by at most the sum of those half
  // ulps, and by 480 × |float(1/60) − 1/60| = 4.2e-7 m from Box2D's float dt: 5.6e-5 m, bound
  // (computed below along motus's path). Measured, over every step: 1.0014e-5 m, the sum of
  // float's roundings of −1 + k/60 (Box2D is at 5.00001 m after step 360). Velocities are ±1 m/s in
  // both, exactly (float holds ±1; e = 1 reverses it): measured 0, bound one float ulp at 1 m/s.
  auto motus = built("motus", scene, 1.0 / 60);
  auto box2d = built("box2d", scene, 1.0 / 60);
  const double h = 1.0 / 60, h_float = static_cast<float>(h);
  double bound = 480 * std::abs(h_float - h), farthest = 0, fastest = 0;
  Snapshot sm, sb;
  for (int i = 1; i <= 480; ++i) {
    motus->step();
    box2d->step();
    motus->read(sm);
    box2d->read(sb);
    int exponent;
    std::frexp(sm.x[0], &exponent);                 // |x| in [2^(e−1), 2^e): float's ulp there is 2^(e−24)
    bound += 0.5 * std::ldexp(1.0, exponent - 24);  // (the other point's path is this one's mirror image)
    for (size_t k : {0u, 2u}) {
      farthest = std::max(farthest, std::abs(sb.x[k] - sm.x[k]));
      fastest = std::max(fastest, std::abs(sb.v[k] - sm.v[k]));
    }
  }
  std::printf("  points: Box2D's largest distance from motus %.6e m (float's bound %.3e m), speed %.3e m/s\n", farthest,
              bound, fastest);
  EXPECT_NEAR(sm.x[0], 3, 1e-9);
  EXPECT_NEAR(sm.x[2], -3, 1e-9);
  EXPECT_LE(farthest, bound);
  EXPECT_LE(fastest, 0x1p-23);  // float's ulp at 1 m/s
  EXPECT_EQ(sb.v[0], -1);
  EXPECT_EQ(sb.v[2], 1);
}

// ---- contacts: Box2D's own solver, measured

TEST(Box2dContacts, HeadOnIsExactInVelocity) {
  // head_on: masses 1 and 3 at ±1 m/s, e = 1. Analytic (1-D elastic collision): the light
  // ball leaves at −2 m/s, the heavy one stops. Box2D, measured: (−2, 0) and (0, 0)
  // exactly (deviation 0: the normal is the line of centres however deep the overlap).
  const SceneDescription scene = load("head_on");
  auto box2d = built("box2d", scene, scene.dt);
  Snapshot s0;
  box2d->read(s0);
  const Snapshot s = run(*box2d, steps_of(scene));
  const double deviation = std::max({std::abs(s.v[0] + 2), std::abs(s.v[1]), std::abs(s.v[2]), std::abs(s.v[3])});
  EXPECT_LE(deviation, 1e-6);  // measured 0; float's ulp at 2 is 2.4e-7
  // Momentum (−1·1 + 3·1 = 2 along x) kept to float precision (measured: exactly).
  EXPECT_NEAR(momentum(scene, s, 0), momentum(scene, s0, 0), 1e-6);
  EXPECT_NEAR(momentum(scene, s, 1), 0, 1e-6);
  // Positions: Box2D finds the contact at the start of a step in which the balls already
  // overlap (they close 2 cm per step; neither is a bullet, moving a fiftieth of its radius in
  // a step) and pushes the overlap apart with its position solver. So the bounce comes up to
  // a step late: the light ball ends at most dt·|Δv| = 0.01 s × 3 m/s = 3 cm from the exact
  // −5.5 m, the heavy one dt·1 m/s = 1 cm from 0.5 m, give or take the overlap the position
  // solver leaves (b2_linearSlop, 5 mm). Measured at t = 4 s: −5.46999693 and 0.49000 m.
  constexpr double slop = 0.005;  // b2_linearSlop
  EXPECT_NEAR(s.x[0], -5.5, 0.03 + slop);
  EXPECT_NEAR(s.x[2], 0.5, 0.01 + slop);
  EXPECT_GT(std::abs(s.x[0] + 5.5), 1e-3);  // measured 0.0300: not the exact answer
}

TEST(Box2dContacts, ObliqueKeepsMomentumButTiltsTheNormal) {
  // oblique: equal balls, impact parameter 0.5 (half the sum of the radii), e = 1.
  // Analytic: they leave at 90°, (0.25, √3/4) and (0.75, −√3/4) m/s (motus: to 1e-12,
  // test_collisions). Box2D, measured: (0.2526269, 0.4345187) and (0.7473731, −0.4345187):
  // a deviation of |Δv| = 3.028e-3 m/s for each ball. Box2D takes the contact normal at
  // the start of the step in which it finds the overlap (the balls close 1 cm per step;
  // here they overlap by 5.2 mm), tilted by about 0.17° from the normal at first touch.
  const SceneDescription scene = load("oblique");
  auto box2d = built("box2d", scene, scene.dt);
  Snapshot s0;
  box2d->read(s0);
  const Snapshot s = run(*box2d, steps_of(scene));
  const double r3 = std::sqrt(3.0) / 4;
  const double dev0 = std::hypot(s.v[0] - 0.25, s.v[1] - r3), dev1 = std::hypot(s.v[2] - 0.75, s.v[3] + r3);
  constexpr double measured = 3.028e-3;
  for (double dev : {dev0, dev1}) {
    EXPECT_LE(dev, 2 * measured);
    EXPECT_GE(dev, 0.5 * measured);  // not zero today: a change is noticed
  }
  // Momentum kept to float precision (measured: exactly); energy measured −5.05e-8 relative.
  EXPECT_NEAR(momentum(scene, s, 0), momentum(scene, s0, 0), 1e-6);
  EXPECT_NEAR(momentum(scene, s, 1), momentum(scene, s0, 1), 1e-6);
  EXPECT_NEAR(kinetic_energy(scene, s) / kinetic_energy(scene, s0) - 1, 0, 1e-6);
  // The outgoing directions are still perpendicular to within the tilt: v0·v1 ≈ 0.
  // Measured 0.2526269·0.7473731 − 0.4345187² = 2.0e-6 (m/s)².
  EXPECT_NEAR(s.v[0] * s.v[2] + s.v[1] * s.v[3], 0, 1e-4);
}

TEST(Box2dContacts, NewtonsCradleSpreadsTheMomentum) {
  // newtons_cradle: four balls at rest touching in a row, a fifth arriving at 1 m/s.
  // motus (contacts at the same instant resolved in order): the last leaves at 1 m/s and
  // the others stop, to 1e-9.
  const SceneDescription scene = load("newtons_cradle");
  const Snapshot m = run(*built("motus", scene, scene.dt), steps_of(scene));
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.v[2 * static_cast<size_t>(i)], 0, 1e-9) << "ball " << i;
  EXPECT_NEAR(m.v[8], 1, 1e-9);
  // Box2D, measured after 3 s: (−0.5731, 0.3569, 0.3711, 0.4023, 0.4428) m/s. Its solver
  // treats the touching row as one simultaneous system: only the first contact is
  // approaching, so only it gets a restitution target, and the iterations spread the
  // impulse down the row instead of passing it on; the first ball rebounds. Momentum is
  // kept (sum = 1), kinetic energy is not: measured −4.86%.
  const Snapshot b = run(*built("box2d", scene, scene.dt), steps_of(scene));
  const double measured[5] = {-0.573059082, 0.3568692207, 0.3710904121, 0.4022521973, 0.4428472519};
  for (size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(b.v[2 * i], measured[i], 0.02) << "ball " << i;
    EXPECT_NEAR(b.v[2 * i + 1], 0, 1e-6) << "ball " << i;
  }
  EXPECT_NEAR(momentum(scene, b, 0), 1, 1e-5);
  const double energy_change = kinetic_energy(scene, b) / 0.5 - 1;  // it starts with ½·1·1² J
  EXPECT_LE(energy_change, -0.0486 / 2);
  EXPECT_GE(energy_change, -0.0486 * 2);
}

TEST(Box2dContacts, BallGasEnergyDriftIsMeasuredAndMotusKeepsIt) {
  // ball_gas (peers.md: 400 balls of radius 0.5, spacing 2, velocities in [−1, 1]², no
  // gravity, e = 1 with each other and with the box, 1/60 s steps), 600 steps.
  // Box2D, measured: −1.71238e-8 after 600 steps (float's rounding). No ball is a bullet: the
  // collisions speed some up, but the fastest ball of Box2D's run (measured 2.39 m/s, checked
  // below) moves 0.080 of its radius in a step, far from the radius. With every ball a bullet, as
  // the adapter had them until 2026-12-07, the same run gained +4.79317e-3, all of it in step 202,
  // from a time-of-impact sub-step (ball 361 meeting ball 380 against the left wall): a setting the
  // fair comparison does not call for (Bullet's CCD engages only past the radius).
  const SceneDescription scene = load("ball_gas");
  ASSERT_EQ(scene.mechanical->bodies.size(), 400u);
  double drift[2], fastest = 0;
  int k = 0;
  for (const char* engine : {"box2d", "motus"}) {
    auto b = built(engine, scene, scene.dt);
    Snapshot s0, s;
    b->read(s0);
    for (int i = 0; i < 600; ++i) {
      b->step();
      b->read(s);
      if (k == 0)
        for (size_t j = 0; j < 400; ++j) fastest = std::max(fastest, std::hypot(s.v[2 * j], s.v[2 * j + 1]));
    }
    drift[k++] = kinetic_energy(scene, s) / kinetic_energy(scene, s0) - 1;
    if (k == 1) {
      EXPECT_FALSE(has_line_containing(b->notes(), "bullets: "));
    }
  }
  const double radius = scene.mechanical->bodies[0].radius;
  std::printf("  ball_gas: Box2D's fastest ball %.3f m/s, %.3f of a radius a step\n", fastest, fastest * scene.dt / radius);
  EXPECT_LT(fastest * scene.dt, radius);  // never a bullet
  constexpr double measured_box2d = -1.71238e-8;
  EXPECT_LE(drift[0], measured_box2d / 2);
  EXPECT_GE(drift[0], measured_box2d * 2);
  // motus: exact impulses keep the energy to rounding: measured 1.55e-15, within
  // motus_gas_rounding_bound's 2.5e-13 for the run's 1,425 ball collisions (f = 0.043).
  std::printf("  motus: drift %.3e\n", drift[1]);
  EXPECT_LE(std::abs(drift[1]), motus_gas_rounding_bound(scene, 600));
  EXPECT_LE(std::abs(drift[1]), std::abs(drift[0]));
}

TEST(Box2dContacts, AFastBallIsABulletAndDoesNotPassThrough) {
  // Two balls of radius 0.5 head-on at ±100 m/s, 60 Hz: each moves 1.67 m a step, more than its
  // radius, so each is a bullet for those steps (as Bullet arms its CCD past the radius). By
  // discrete detection alone they would be past each other's centre after the second step (at
  // ±0.33 m, swapped) and be pushed on through. As bullets they meet at the time of impact and
  // stay in their order, bouncing apart at their full 100 m/s (e = 1; measured: the energy
  // exactly kept, where Bullet's CCD stops both dead).
  auto box2d = built("box2d", two_balls_head_on(100), 1.0 / 60);
  const Snapshot p = run(*box2d, 10);
  EXPECT_LT(p.x[0], p.x[2]);
  EXPECT_NEAR(p.v[0], -100, 1e-3);  // bounced back, not through (float: 1e-5 relative)
  EXPECT_NEAR(p.v[2], 100, 1e-3);
  EXPECT_TRUE(has_line_containing(box2d->notes(), "bullets: "));
  // The same pair at ±1 m/s (a sixtieth of a metre a step) is never a bullet: nothing said.
  auto slow = built("box2d", two_balls_head_on(1), 1.0 / 60);
  run(*slow, 200);
  EXPECT_FALSE(has_line_containing(slow->notes(), "bullets: "));
}

// The bullet rule at its threshold (box2d_backend.cpp, step()): a ball is a bullet in a step where
// it moves more than its radius, at the velocity the step's kick gives it, and the note counts those
// body-steps. Balls of radius 0.5 at 60 Hz: the threshold is 0.5 m a step, 30 m/s.
TEST(Box2dContacts, ABallIsABulletInExactlyTheStepsItMovesMoreThanItsRadius) {
  // No gravity: one ball at 0.9 radius a step (27 m/s) and one at 1.1 (33 m/s), 100 m apart on
  // parallel lines, no walls (they never meet). 60 steps: the slow one is never a bullet, the fast
  // one in every step: 0 + 60 body-steps.
  SceneDescription pair = one_body({0, 0}, {0.9 * 0.5 * 60, 0});
  BodyDescription fast = pair.mechanical->bodies[0];
  fast.position = {0, 100};
  fast.velocity = {1.1 * 0.5 * 60, 0};
  pair.mechanical->bodies.push_back(fast);
  auto box2d = built("box2d", pair, 1.0 / 60);
  run(*box2d, 60);
  EXPECT_TRUE(has_line_containing(box2d->notes(), "bullets: 60 body-steps of a ball moving more than its radius"))
      << ::testing::PrintToString(box2d->notes());
  // The slow one alone: no bullet step, and nothing said.
  auto slow = built("box2d", one_body({0, 0}, {0.9 * 0.5 * 60, 0}), 1.0 / 60);
  run(*slow, 60);
  EXPECT_FALSE(has_line_containing(slow->notes(), "bullets: ")) << ::testing::PrintToString(slow->notes());
  // The kick counts: a ball thrown level at 0.99 radius a step (29.7 m/s) under g = 10 m/s² has,
  // after the kick of step k, the speed √(29.7² + (10k/60)²), past 30 m/s once (k/6)² > 900 − 882.09
  // = 17.91, k > 25.39: a bullet in steps 26 to 60, 35 of them (its velocity before the kick would
  // make it 34, from step 27). The margins, 0.55 and 0.87 (m/s)² either side of 900, are far above
  // float's rounding of the velocity (1e-5 (m/s)²).
  auto kicked = built("box2d", with_peers_gravity(one_body({0, 0}, {0.99 * 0.5 * 60, 0})), 1.0 / 60);
  run(*kicked, 60);
  EXPECT_TRUE(has_line_containing(kicked->notes(), "bullets: 35 body-steps of a ball moving more than its radius"))
      << ::testing::PrintToString(kicked->notes());
}

TEST(Box2dContacts, RestitutionIsTheProductNotTheMax) {
  // drop: a ball of e = 0.8 falls 10 m onto a floor of e = 1. motus's pair e is the
  // product, 0.8; Box2D's own max(0.8, 1) = 1 would bounce it back at full speed. The
  // PreSolve listener makes it 0.8: the first bounce leaves at 0.8 times the speed the
  // ball had after the step's gravity kick (measured ratio 0.80000012, float).
  const SceneDescription scene = load("drop");
  auto box2d = built("box2d", scene, scene.dt);
  Snapshot s, before;
  box2d->read(s);
  for (int i = 0; i < 3000; ++i) {
    before = s;
    box2d->step();
    box2d->read(s);
    if (before.v[1] < 0 && s.v[1] > 0) break;
  }
  ASSERT_GT(s.v[1], 0) << "no bounce within 3 s";
  const double approach = before.v[1] - 9.81 * scene.dt;  // the velocity the solver sees
  EXPECT_NEAR(s.v[1] / -approach, 0.8, 1e-5);
  // The speed at impact: √(2·9.81·10) = 14.007 m/s (measured 14.0089 before the kick).
  EXPECT_NEAR(-approach, std::sqrt(2 * 9.81 * 10), 0.03);
}

TEST(Box2dLimits, TranslationCapIsReported) {
  // A free ball at 300 m/s with 1/60 s steps would move 5 m per step; b2_maxTranslation
  // (2 m per step) slows it to 120 m/s: after 1 s it is at 120 m (motus: 300 m).
  const SceneDescription scene = one_body({0, 0}, {300, 0});
  auto box2d = built("box2d", scene, 1.0 / 60);
  EXPECT_TRUE(has_line_containing(box2d->notes(), "250% of it: Box2D will slow it to the cap"));
  const Snapshot b = run(*box2d, 60);
  EXPECT_NEAR(b.x[0], 120, 1e-3);
  EXPECT_NEAR(b.v[0], 120, 1e-3);
  EXPECT_TRUE(has_line_containing(box2d->notes(), "b2_maxTranslation capped 60 body-steps (first at step 1"));
  const Snapshot m = run(*built("motus", scene, 1.0 / 60), 60);
  EXPECT_NEAR(m.x[0], 300, 1e-9);
  // A slow scene says the cap was not reached, and Box2D's float precision.
  auto slow = built("box2d", one_body({0, 0}, {1, 0}), 1.0 / 60);
  run(*slow, 10);
  EXPECT_TRUE(has_line_containing(slow->notes(), "b2_maxTranslation not reached in 10 steps"));
  EXPECT_TRUE(has_line_containing(slow->notes(), "Box2D is float"));
  // Timed (compare's timing rounds), a step does only Box2D's work: nothing is watched for the
  // notes, and the same run moves the same.
  auto timed = built("box2d", scene, 1.0 / 60);
  timed->watch_for_notes(false);
  const Snapshot t = run(*timed, 60);
  EXPECT_EQ(t.x, b.x);
  EXPECT_FALSE(has_line_containing(timed->notes(), "b2_maxTranslation capped"));
}

TEST(Box2dLimits, StickPendulumKeepsItsStickAndPin) {
  // stick_pendulum: a 1 m stick from a pinned body. Box2D: the pinned body is static at
  // the pin (exactly 0, 0) and the rigid distance joint keeps the length to float
  // precision: measured worst error 1.15e-7 over 600 steps.
  const SceneDescription scene = load("stick_pendulum");
  auto box2d = built("box2d", scene, scene.dt, Integrator::Verlet);
  double worst = 0;
  Snapshot s;
  for (long i = 0; i < steps_of(scene); ++i) {
    box2d->step();
    box2d->read(s);
    worst = std::max(worst, std::abs(std::hypot(s.x[2] - s.x[0], s.x[3] - s.x[1]) - 1));
  }
  EXPECT_LE(worst, 1e-6);
  EXPECT_EQ(s.x[0], 0);
  EXPECT_EQ(s.x[1], 0);
  EXPECT_EQ(s.v[0], 0);
  EXPECT_TRUE(has_line_containing(box2d->settings(), "pins: the pinned body is a static body"));
  // The note's worst is the one measured here from the positions read, as the table's column takes it (the
  // backend's own float subtraction had made it read 1.26e-5 % beside this 1.15e-7).
  char expected[96];
  std::snprintf(expected, sizeof expected, "sticks: the worst length error so far is %.3g%% of the rest length", 100 * worst);
  EXPECT_TRUE(has_line_containing(box2d->notes(), expected)) << expected;
}

// A run that blows up (the rope unpinned under a gravity of 1e300 m/s², past float): its sticks' lengths stop being
// numbers, which the table's constraint column shows as inf. The note said "the worst length error
// so far is 0% of the rest length (after step 0 …)": NaN > worst is false, and it kept the start.
TEST(Box2dLimits, TheSticksNoteOfARunThatBlewUpSaysItsErrorIsNotFinite) {
  const SceneDescription scene = load("rope", {"forces[0].g=[0,-1e300]", "rope.pin_first=false"});
  auto box2d = built("box2d", scene, scene.dt, Integrator::Verlet);
  for (int i = 0; i < 5; ++i) box2d->step();
  EXPECT_TRUE(has_line_containing(box2d->notes(), "sticks: the worst length error so far is inf% of the rest length (after step 1;"));
}

// The float note's scale is the farthest a body came, not where the bodies started: a body thrown
// at 300 m/s from the origin was "0 m from the origin" (about 1e-7 m of rounding) while it flew
// 400 m, where float rounds to some 5e-5 m.
TEST(Box2dLimits, TheFloatNoteScalesWithTheFarthestABodyCame) {
  SceneDescription scene = load("free_fall");
  scene.mechanical->bodies[0].velocity[0] = 300;
  auto box2d = built("box2d", scene, scene.dt, Integrator::SymplecticEuler);
  Snapshot s;
  double farthest = 0;
  for (long i = 0; i < steps_of(scene); ++i) {
    box2d->step();
    box2d->read(s);
    farthest = std::max(farthest, std::hypot(s.x[0], s.x[1]));
  }
  ASSERT_GT(farthest, 100);
  char expected[64];
  std::snprintf(expected, sizeof expected, "at %.3g m from the origin", farthest);
  EXPECT_TRUE(has_line_containing(box2d->notes(), expected)) << expected;
}

// ---- what Box2D cannot run

TEST(Box2dUnsupported, ThreeDimensionalScenesAreRefused) {
  auto box2d = make_backend("box2d");
  const SceneDescription gas3 = load("ball_gas_3d");
  try {
    box2d->build(gas3, Integrator::SymplecticEuler, gas3.dt);
    FAIL() << "a 3-D scene was accepted";
  } catch (const Unsupported& e) {
    EXPECT_STREQ(e.what(), "not supported by box2d: 3-D scenes");
    EXPECT_EQ(e.engine(), "box2d");
    EXPECT_EQ(e.elements(), std::vector<std::string>{"3-D scenes"});
  }
}

TEST(Box2dUnsupported, BodyStartingOutsideAWallIsRefused) {
  // motus moves such a body onto the wall's surface; a Box2D edge would hold it on the
  // wall's side, a different scene: refused, naming the body and the wall.
  SceneDescription scene = with_peers_gravity(one_body({0, -1}, {0, 0}));
  scene.mechanical->colliders.planes.push_back({{0, 1, 0}, 0, 1});
  const auto why = refused("box2d", scene, Integrator::SymplecticEuler);
  ASSERT_EQ(why.size(), 1u) << "accepted, or refused for more than this";
  EXPECT_NE(why[0].find("body 0 starting outside plane 0"), std::string::npos) << why[0];
}

TEST(Box2dUnsupported, ABodyPinnedAwayFromItsStartIsRefused) {
  // motus moves it to the pin at the first step; Box2D would make it there: other starting states.
  SceneDescription scene = one_body({0, 0}, {0, 0});
  scene.mechanical->pins.push_back({0, {0, 1, 0}});
  const auto why = refused("box2d", scene, Integrator::Verlet);
  ASSERT_EQ(why.size(), 1u) << "accepted, or refused for more than this";
  EXPECT_NE(why[0].find("body 0 pinned away from where it starts"), std::string::npos) << why[0];
}

TEST(Box2dUnsupported, AMassFloatCannotHoldIsRefused) {
  // Box2D keeps masses in float and makes a mass ≤ 0 into 1 kg: 1e-50 kg would be 1 kg.
  SceneDescription scene = one_body({0, 1}, {0, 0});
  scene.mechanical->bodies[0].mass = 1e-50;
  const auto why = refused("box2d", scene, Integrator::SymplecticEuler);
  ASSERT_EQ(why.size(), 1u) << "accepted, or refused for more than this";
  EXPECT_NE(why[0].find("body 0: a mass of 1e-50 kg"), std::string::npos) << why[0];
}

// A plane is an edge as long as the bodies' spread along it and then some: two balls 3·10⁴ m
// apart resting on the floor both stay on it (a fixed 10⁴ m each side of their centroid had
// both beyond its ends, and they fell through).
TEST(Box2dBackend, APlaneHoldsBodiesFarApartAlongIt) {
  SceneDescription scene = with_peers_gravity(one_body({0, 0.5}, {0, 0}));
  BodyDescription far = scene.mechanical->bodies[0];
  far.position = {30000, 0.5};
  scene.mechanical->bodies.push_back(far);
  scene.mechanical->colliders.planes.push_back({{0, 1, 0}, 0, 1});
  auto box2d = make_backend("box2d");
  box2d->build(scene, Integrator::SymplecticEuler, 0.01);
  const Snapshot s = run(*box2d, 100);
  // (Float positions near 3·10⁴ m are 0.002 m apart: the balls rest within a few of those.)
  EXPECT_GT(s.x[1], 0.5 - 0.02);
  EXPECT_GT(s.x[3], 0.5 - 0.02);
}

TEST(Box2dBackend, VersionAndFairSettings) {
  auto box2d = make_backend("box2d");
  EXPECT_EQ(box2d->name(), "box2d");
  EXPECT_EQ(box2d->version(), "Box2D 2.4.1, float");
  const auto settings = box2d->settings();  // peers.md's fair settings
  EXPECT_TRUE(has_line_containing(settings, "world.Step(dt, 8, 3)"));
  EXPECT_TRUE(has_line_containing(settings, "restitution threshold: 0 m/s"));
  EXPECT_TRUE(has_line_containing(settings, "sleep: off"));
  EXPECT_TRUE(has_line_containing(settings, "damping: 0"));
  EXPECT_TRUE(has_line_containing(settings, "friction: 0"));
  EXPECT_TRUE(has_line_containing(settings, "the product eA*eB"));
}

}  // namespace

TEST(Box2dLimits, TheCapIsReportedWhenTheCappedBallAlsoHitsSomethingWithinItsStep) {
  // Found by an audit (its scene): three balls in a 10 m box under gravity, one at 1e5 m/s (1000 m a
  // step at 0.01 s: the cap, 2 m, slows it from the first step). The capped ball hit something
  // within its step, so no step ended at the cap's speed, none was counted, and the note said
  // "b2_maxTranslation not reached in 500 steps (… 5e+04% of it …)" while Box2D lost all the energy.
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("motus_fast_ball_" + std::to_string(::getpid()) + ".json");
  {
    std::ofstream out(file);
    out << R"({"name": "three_balls", "dimensions": 2,
      "bodies": [
        {"mass": 1, "radius": 0.5, "position": [2, 5], "velocity": [100000, 0]},
        {"mass": 2, "radius": 0.7, "position": [5, 5], "velocity": [0, 1]},
        {"mass": 1, "radius": 0.5, "position": [8, 5], "velocity": [-3, 2]}],
      "forces": [{"type": "gravity", "g": [0, -9.81]}],
      "colliders": [{"type": "box", "min": [0, 0], "max": [10, 10]}],
      "integrator": "symplectic-euler", "dt": 0.01, "duration": 5})";
  }
  const SceneDescription scene = motus::load_scene(file.string());
  std::filesystem::remove(file);
  auto box2d = built("box2d", scene, scene.dt);
  run(*box2d, 500);
  const auto notes = box2d->notes();
  std::string all;
  for (const auto& n : notes) all += n + "\n";
  EXPECT_FALSE(has_line_containing(notes, "not reached")) << all;
  EXPECT_TRUE(has_line_containing(notes, "(first at step 1,")) << all;
  EXPECT_TRUE(has_line_containing(notes, "Box2D will slow it to the cap")) << all;
}
