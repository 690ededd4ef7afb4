// Simulation's clock for fixed steps (simulation.hpp, advance): a caller that advances to
// t0 + k·dt one step per call — as compare's motus column does, to step alongside the peers'
// world.Step(dt) — takes exactly one step per call and reads exactly t0 + k·dt, however many
// calls. (Summed call by call, the clock drifted a rounding per call; at dt = 0.01 the gap passed
// the step count's 1e-9 at the 17,042nd call, which then took two steps: a compare of 200 s ran
// motus one step longer than the peers, and measured it against them one step ahead.)
#include <gtest/gtest.h>

#include "motus/simulation.hpp"

namespace {

using namespace motus;

// One ball flying at 1 m/s with nothing in its way: its position is the time.
SceneDescription free_flight(double start_time) {
  SceneDescription scene;
  MechanicalDescription m;
  m.dimensions = 1;
  BodyDescription b;
  b.position = {0};
  b.velocity = {1};
  m.bodies.push_back(b);
  scene.mechanical = m;
  scene.start_time = start_time;
  scene.dt = 0.01;
  return scene;
}

TEST(SimulationClock, OneStepACallLandsOnEveryStepsTimeForTwentyThousandSteps) {
  for (const double t0 : {0.0, 3.7}) {
    Simulation sim(free_flight(t0), Integrator::SymplecticEuler);
    const double dt = 0.01;
    constexpr long kSteps = 20000;  // (past the 17,042nd call, where the summed clock took two)
    long first_wrong = -1;
    for (long k = 1; k <= kSteps && first_wrong < 0; ++k) {
      sim.advance(t0 + static_cast<double>(k) * dt, dt, {});
      if (sim.steps() != k || sim.time() != t0 + static_cast<double>(k) * dt) first_wrong = k;
    }
    EXPECT_EQ(first_wrong, -1) << "t0 = " << t0 << ": call " << first_wrong << " ended at step " << sim.steps()
                               << ", t = " << sim.time();
    // The flight itself: x = v·(t − t0) after kSteps steps of dt (to the steps' rounding).
    EXPECT_NEAR(sim.state()[0], static_cast<double>(kSteps) * dt, 1e-9);
  }
}

TEST(SimulationClock, AnotherStepSizeStartsTheClockWhereTheLastOneEnded) {
  Simulation sim(free_flight(0), Integrator::SymplecticEuler);
  sim.advance(1.0, 0.1, {});  // ten steps of 0.1
  EXPECT_EQ(sim.steps(), 10);
  const double t1 = sim.time();
  for (long k = 1; k <= 100; ++k) sim.advance(t1 + static_cast<double>(k) * 0.01, 0.01, {});
  EXPECT_EQ(sim.steps(), 110);
  EXPECT_EQ(sim.time(), t1 + 100 * 0.01);
  // And a target short of the next step by less than its 1e-9 takes no step (nor goes back).
  sim.advance(sim.time() + 1e-13, 0.01, {});
  EXPECT_EQ(sim.steps(), 110);
}

}  // namespace
