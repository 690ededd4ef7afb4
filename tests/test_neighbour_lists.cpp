// The collision pass's neighbour lists (ball_collisions.hpp): each step tests only the pairs on
// lists built several steps before, so a contact they missed would not be found at all. Here
// gases of up to 64 balls (the most "exact": "free-flight" solves) are stepped by motus and
// compared with free-flight's answer, which looks at every pair at every event and has no broad
// phase; any missed contact, or one found that is not there, shows as a ball metres from where
// the event-by-event answer has it. The gases are chosen to go through what the lists handle:
// lists that last many steps, balls that leave them (faster than a radius per step), balls of
// different sizes, and a drift given another array of positions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "motus/ball_lattice.hpp"
#include "motus/collide/ball_collisions.hpp"
#include "motus/exact/free_flight.hpp"
#include "motus/simulation.hpp"

namespace {

using motus::Integrator;
using motus::SceneDescription;
using motus::Simulation;

// `count` balls of radius 0.5 on a lattice of spacing 2 in their box, velocities uniform in
// [−speed, speed]^d (ball_lattice.hpp), no gravity, e = 1.
SceneDescription gas_in_a_box(int dimensions, long count, double speed) {
  SceneDescription scene;
  motus::MechanicalDescription m;
  m.dimensions = dimensions;
  motus::BallLattice lattice;
  lattice.count = count;
  lattice.speed = speed;
  lattice.container = true;
  motus::add_ball_lattice(m, lattice);
  scene.mechanical = std::move(m);
  scene.integrator = "symplectic-euler";
  scene.dt = 1.0 / 60;
  return scene;
}

struct Outcome {
  double worst = 0;  // the largest difference from the event-by-event answer, in any coordinate
  long ball_collisions = 0, grid_builds = 0, steps = 0;
};

Outcome against_free_flight(const SceneDescription& scene, double duration) {
  Simulation sim(scene, Integrator::SymplecticEuler);
  sim.advance(duration, scene.dt, {});
  const std::optional<motus::Vector> exact = motus::free_flight_state(scene, sim.time());
  EXPECT_TRUE(exact.has_value());
  Outcome run;
  if (exact) run.worst = (sim.state() - *exact).cwiseAbs().maxCoeff();
  run.ball_collisions = sim.world()->collision_counters().ball_collisions;
  run.grid_builds = sim.world()->collision_counters().grid_builds;
  run.steps = sim.steps();
  std::printf("  %d-D, %zu balls, %g s: the largest difference from the event-by-event answer %.1e m\n",
              scene.mechanical->dimensions, scene.mechanical->bodies.size(), duration, run.worst);
  return run;
}

// Differences from rounding grow with every contact (each turns a small error in where two balls
// meet into a larger one in where they go: a gas is chaotic), by about ten times every second
// in the slow gas and every few hundredths of a second in the quick one. So each run stops while
// they are still below kSameAnswer = 1e-8 m (the largest, printed by each test: 6.2e-11 m in the
// slow gas, 2.4e-10 m with the balls faster than a radius a step, 1.2e-9 m in the fast gas's 8
// steps, 2.7e-11 m with balls of different sizes, 2.1e-13 m in the big gas; motus before the
// lists gave the same numbers to the bit). A missed contact puts a ball centimetres to metres off.
constexpr double kSameAnswer = 1e-8;

TEST(NeighbourLists, AGasInABoxFollowsTheEventByEventAnswerWhileTheListsLastManySteps) {
  for (int d : {2, 3}) {
    // peers.md's ball gas (speeds in [−1, 1]): the lists' skin covers about eight steps of the
    // fastest ball, so they are built again every few steps, not every step.
    const SceneDescription scene = gas_in_a_box(d, 64, 1);
    const Outcome run = against_free_flight(scene, 6);
    EXPECT_LT(run.worst, kSameAnswer) << d << "-D";
    EXPECT_GT(run.ball_collisions, 20) << d << "-D: the gas must collide for this to say anything";
    EXPECT_LT(run.grid_builds, run.steps / 3) << d << "-D: the lists must serve several steps";
  }
}

TEST(NeighbourLists, BallsFasterThanARadiusPerStepLeaveTheListsAndMissNothing) {
  for (int d : {2, 3}) {
    // A quick gas, and every fifth ball faster than a radius per step (0.5 m at 60 Hz is 30 m/s):
    // those search along their paths, and balls they speed up leave the lists until they are
    // built again.
    SceneDescription scene = gas_in_a_box(d, 64, 4);
    auto& bodies = scene.mechanical->bodies;
    for (size_t i = 0; i < bodies.size(); i += 5)
      for (double& u : bodies[i].velocity) u *= 12;
    const Outcome run = against_free_flight(scene, 0.25);
    EXPECT_LT(run.worst, kSameAnswer) << d << "-D";
    EXPECT_GT(run.ball_collisions, 60) << d << "-D";
  }
}

TEST(NeighbourLists, AGasOfFastBallsFindsEachOtherInTheGridOfTheirPathsAndMissesNothing) {
  for (int d : {2, 3}) {
    // Every ball's velocity twelve times the quick gas's, up to 48 m/s a component: about two
    // thirds of them (every ball in 3-D but a few) move farther than their radius in a step,
    // more than enough for the grid of their paths (path_grid.hpp), where each looks for the
    // others instead of testing them all; and those their contacts speed up join them.
    SceneDescription scene = gas_in_a_box(d, 64, 4);
    for (auto& b : scene.mechanical->bodies)
      for (double& u : b.velocity) u *= 12;
    // (Eight steps: in a gas this quick the rounding's differences from the event-by-event answer
    // grow past kSameAnswer in ten — 6e-8 m — with or without the grid, whose pairs' events are
    // the same.)
    Simulation sim(scene, Integrator::SymplecticEuler);
    sim.advance(8 * scene.dt, scene.dt, {});
    const std::optional<motus::Vector> exact = motus::free_flight_state(scene, sim.time());
    ASSERT_TRUE(exact.has_value());
    const double worst = (sim.state() - *exact).cwiseAbs().maxCoeff();
    std::printf("  %d-D, the fast gas, 8 steps: the largest difference from the event-by-event answer %.1e m\n", d, worst);
    EXPECT_LT(worst, kSameAnswer) << d << "-D";
    const auto counters = sim.world()->collision_counters();
    EXPECT_GT(counters.ball_collisions, 100) << d << "-D";
    EXPECT_EQ(counters.path_grids, sim.steps()) << d << "-D: every step has its fast balls find each other in the grid";
  }
}

TEST(NeighbourLists, ThousandsOfFastBallsTestFarFewerPairsThanAllOfThem) {
  // 4,096 balls of radius 0.05 on the lattice of spacing 2, velocities up to 24 m/s a component
  // (0.05 m is 3 m/s at 60 Hz): nearly all are fast every step. Testing each against every
  // other fast ball is F(F − 1) tests a step; in the grid of their paths a ball meets only the
  // few whose paths pass near its own.
  for (int d : {2, 3}) {
    SceneDescription scene = gas_in_a_box(d, 4096, 24);
    for (auto& b : scene.mechanical->bodies) b.radius = 0.05;
    Simulation sim(scene, Integrator::SymplecticEuler);
    const long steps = 3;
    sim.advance(steps * scene.dt, scene.dt, {});
    const auto counters = sim.world()->collision_counters();
    EXPECT_EQ(counters.path_grids, steps) << d << "-D";
    const double fast = 4096 * 0.9;  // (at least: a speed of 3 m/s is 1/8 of the range, fewer than 1 ball in 10 is slower in 2-D)
    EXPECT_LT(static_cast<double>(counters.pair_tests), steps * fast * (fast - 1) / 100) << d << "-D";
  }
}

TEST(NeighbourLists, AGasThatCrossesItsBoxInAStepLooksOnlyNearItsPathsInSpaceAndTime) {
  // peers.md's 400 balls at 2,100 times their speed: the fastest moves about 100 radii (50 m)
  // in a step, across the 40 m box, and every ball is fast. Each ball's line through the whole
  // step passes near every other's, and each contact tested every fast ball (723 pair tests a
  // contact over these two steps). Cut at each ball's first wall contact and into slabs of time
  // (path_grid.hpp), a contact tests only the balls near its two bodies then (64 a contact).
  SceneDescription scene = gas_in_a_box(2, 400, 2100);
  Simulation sim(scene, Integrator::SymplecticEuler);
  sim.advance(2 * scene.dt, scene.dt, {});
  const auto counters = sim.world()->collision_counters();
  const long contacts = counters.ball_collisions + counters.wall_collisions;
  EXPECT_GT(contacts, 4000) << "the gas must collide for this to say anything";
  EXPECT_EQ(counters.path_grids, 2);
  EXPECT_LT(counters.pair_tests, 150 * contacts);
}

TEST(NeighbourLists, TooManyContactsInAFastGasSaysTheBallsAreTooFastNotThatTheyOverlap) {
  // 100 balls at 21,000 times their speed, about 1,000 radii a step: more contacts in a step
  // than the engine allows (1000 + 100 N). Nothing overlaps; the message says what does happen.
  SceneDescription scene = gas_in_a_box(2, 100, 21000);
  Simulation sim(scene, Integrator::SymplecticEuler);
  try {
    sim.advance(scene.dt, scene.dt, {});
    ADD_FAILURE() << "the step should have had too many contacts";
  } catch (const std::exception& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("more than 11000 collisions in one step"), std::string::npos) << message;
    EXPECT_NE(message.find("radii in one step"), std::string::npos) << message;
    EXPECT_EQ(message.find("overlapping"), std::string::npos) << message;
  }
}

TEST(NeighbourLists, BallsOfDifferentSizesAndMassesFollowTheEventByEventAnswer) {
  for (int d : {2, 3}) {
    // Radii from 0.2 to 0.9 (the lists' reach is r_a + r_b + skin, the grid's cells 2·r_max +
    // skin) and masses that go with the volume.
    SceneDescription scene = gas_in_a_box(d, 64, 2);
    auto& bodies = scene.mechanical->bodies;
    for (size_t i = 0; i < bodies.size(); ++i) {
      bodies[i].radius = 0.2 + 0.1 * static_cast<double>(i % 8);
      bodies[i].mass = std::pow(bodies[i].radius / 0.5, d);
    }
    const Outcome run = against_free_flight(scene, 1.5);
    EXPECT_LT(run.worst, kSameAnswer) << d << "-D";
    EXPECT_GT(run.ball_collisions, 80) << d << "-D";
  }
}

TEST(NeighbourLists, ABigGasInOrderOfPlaceOrShuffledFollowsTheEventByEventAnswer) {
  // The pair pass moves each body to the end of the step once no pair left to test has it
  // (ball_collisions.hpp, BallState::lag): a lattice's balls are numbered along its rows, so
  // they go a few hundred at a time, a row or a plane behind the pass; shuffled, almost all go
  // at the end. Balls of radius 0.8 on the lattice of spacing 2 have their lattice neighbours
  // on their lists (reach 1.6 m + skin): 400 balls in 2-D, 343 in 3-D make several of the
  // pass's batches of 256 pairs. A ball moved before its last pair is tested, moved twice, or
  // not at all is metres off.
  for (int d : {2, 3}) {
    for (const bool shuffled : {false, true}) {
      SceneDescription scene = gas_in_a_box(d, d == 2 ? 400 : 343, 1);
      auto& bodies = scene.mechanical->bodies;
      for (auto& b : bodies) b.radius = 0.8;
      if (shuffled)  // (a fixed permutation: 97 has no common factor with 400 or 343)
        for (size_t i = 0; i < bodies.size(); ++i) std::swap(bodies[i], bodies[(i * 97) % bodies.size()]);
      const Outcome run = against_free_flight(scene, 0.5);
      EXPECT_LT(run.worst, kSameAnswer) << d << "-D" << (shuffled ? ", shuffled" : "");
      EXPECT_GT(run.ball_collisions, 100) << d << "-D";
    }
  }
}

TEST(NeighbourLists, ADriftGivenAnotherArrayOfPositionsBuildsThemAgain) {
  // Two balls of radius 0.5, unit masses, e = 1, no walls, steps of 0.2 s at 0.05 m/s: a slow
  // gas, whose lists would hold for many steps. They are built on one array, where the balls
  // are 10 m apart (no pair on them). Then the same collisions are given another array, where
  // the balls are 1.015 m apart and closing at 0.1 m/s: they touch at t = 0.15 s and swap
  // velocities (equal masses, head on), which leaves them at 0.005 and 1.01 m after the step.
  // Lists kept from the first array would let them pass through each other (0.01 and 1.005).
  motus::Vector inverse_mass(2);
  inverse_mass << 1, 1;
  motus::BallCollisions<1> collisions(inverse_mass, {0.5, 0.5}, {1, 1}, motus::Colliders{});
  motus::Vector x(2), v(2);
  x << 0, 10;
  v << 0.05, -0.05;
  collisions.drift(x, v, 0.2);
  motus::Vector y(2), u(2);
  y << 0, 1.015;
  u << 0.05, -0.05;
  collisions.drift(y, u, 0.2);
  EXPECT_EQ(collisions.counters().ball_collisions, 1);
  EXPECT_NEAR(y[0], 0.005, 1e-12);
  EXPECT_NEAR(y[1], 1.01, 1e-12);
  EXPECT_DOUBLE_EQ(u[0], -0.05);
  EXPECT_DOUBLE_EQ(u[1], 0.05);
}

TEST(NeighbourLists, ABallAContactSpeedsUpPastTheOthersShortensTheListsLife) {
  // How long the lists last comes from how fast the slow balls are; with no forces the next
  // step does not read every velocity again but takes the contacts' new speeds into account.
  // A line of five balls of radius 0.5, steps of 1 s, no walls: A (10^6 kg) at 0.05 m/s, the
  // fastest at the start, and then B (1 kg), C (10^-6 kg), E (10^-12 kg) at rest, each hit late
  // in a step (t = 0.9, 1.9, 2.9 s) by the one before and sent off at twice its speed (heavy on
  // light, e = 1): E leaves at 0.4 m/s, eight times A's speed and still below a radius per step,
  // so it stays on the lists. T (1 kg) waits 0.6 m beyond E, outside E's reach when the lists
  // were built (skin 0.5 m); E reaches it at t = 4.4 s and bounces back. Lists kept as long as
  // A's speed alone allows (until t = 5 s) let E pass into T (they end 0.76 m apart, three contacts).
  motus::Vector inverse_mass(5);
  inverse_mass << 1e-6, 1, 1e6, 1e12, 1;
  motus::BallCollisions<1> collisions(inverse_mass, {0.5, 0.5, 0.5, 0.5, 0.5}, {1, 1, 1, 1, 1},
                                      motus::Colliders{});
  motus::Vector x(5), v(5);
  x << 0, 1.045, 2.145, 3.345, 4.945;  // surface gaps 0.045, 0.1, 0.2 and 0.6 m
  v << 0.05, 0, 0, 0, 0;
  for (int step = 0; step < 5; ++step) collisions.drift(x, v, 1.0, false);
  for (int i = 0; i + 1 < 5; ++i) EXPECT_GE(x[i + 1] - x[i], 1 - 1e-12) << "balls " << i << " and " << i + 1;
  // Five contacts: A–B, B–C, C–E, E–T, and E, on its way back at 0.4 m/s, off C, coming at
  // 0.2 m/s, which sends it forward at 2 · 0.2 + 0.4 = 0.8 m/s (to within the light balls'
  // masses, 10^-6 of the speeds). T has taken 2 · 10^-12 · 0.4 kg m/s.
  EXPECT_EQ(collisions.counters().ball_collisions, 5);
  EXPECT_NEAR(v[3], 0.8, 1e-5);
  EXPECT_NEAR(v[4], 8e-13, 1e-17);
}

}  // namespace
