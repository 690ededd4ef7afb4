// Measured stability on x'' = −ω²x against tests/reference/integrators.md,
// "Stability on x'' = −ω² x, with z = ω h":
//   explicit Euler: never bounded, energy × (1 + z²) per step
//   midpoint: never bounded, |R|² = 1 + z⁴/4 per step
//   symplectic Euler (both), velocity Verlet, position Verlet: bounded for z < 2
//   RK4: bounded for z ≤ 2√2 (|R|² = 1 − z⁶/72 + z⁸/576)
// Limits are measured by bisection on z; each must be within 1% of theory (the issue).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "motus/integrate/integrator_catalog.hpp"
#include "test_scenes.hpp"

namespace {

using motus::Integrator;

constexpr double kOmega = 1;  // ω; z = ω h
constexpr long kSteps = 10000;
constexpr double kGrowth = 1000;  // "blown up": amplitude above 1000× its start

// Amplitude √(x² + v²/ω²); the start (1, 0) has amplitude 1.
double amplitude(const motus::Vector& y) { return std::hypot(y[0], y[1] / kOmega); }

// Whether kSteps steps of h = z/ω keep the amplitude within kGrowth× its start.
bool stays_bounded(Integrator integrator, double z) {
  const double h = z / kOmega;
  motus::Simulation sim(motus_test::oscillator(kOmega), integrator);
  bool bounded = true;
  sim.advance(static_cast<double>(kSteps) * h, h, motus::Tolerance{}, [&](const motus::Simulation& s) {
    if (!(amplitude(s.state()) <= kGrowth)) bounded = false;  // NaN and inf count as blown up
  });
  EXPECT_EQ(sim.steps(), kSteps);
  return bounded;
}

// Bisection for the boundary between bounded (below) and blown up (above).
double measured_limit(Integrator integrator, double theory) {
  double lo = 0.5 * theory, hi = 1.5 * theory;
  EXPECT_TRUE(stays_bounded(integrator, lo));
  EXPECT_FALSE(stays_bounded(integrator, hi));
  for (int i = 0; i < 30; ++i) {
    const double mid = 0.5 * (lo + hi);
    (stays_bounded(integrator, mid) ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

struct LimitCase {
  Integrator integrator;
  double theory;  // integrators.md
};

class StabilityLimit : public ::testing::TestWithParam<LimitCase> {};

TEST_P(StabilityLimit, WithinOnePercentOfTheory) {
  const auto c = GetParam();
  const double z = measured_limit(c.integrator, c.theory);
  std::printf("  %-20s measured limit z = %.6f, theory %.6f, relative difference %.2e\n",
              motus::info(c.integrator).name, z, c.theory, std::abs(z - c.theory) / c.theory);
  EXPECT_LT(std::abs(z - c.theory) / c.theory, 0.01);  // the issue: within 1% of theory
  // Just inside the limit bounded, just outside blown up (integrators.md).
  EXPECT_TRUE(stays_bounded(c.integrator, 0.99 * c.theory));
  EXPECT_FALSE(stays_bounded(c.integrator, 1.01 * c.theory));
}

std::string case_name(const ::testing::TestParamInfo<LimitCase>& info) {
  std::string name = motus::info(info.param.integrator).name;
  for (char& ch : name)
    if (ch == '-') ch = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(
    Theory, StabilityLimit,
    ::testing::Values(LimitCase{Integrator::SymplecticEuler, 2},   // integrators.md: z < 2
                      LimitCase{Integrator::SymplecticEulerX, 2},  // z < 2
                      LimitCase{Integrator::Verlet, 2},            // z < 2
                      LimitCase{Integrator::VelocityVerlet, 2},    // z < 2
                      LimitCase{Integrator::Rk4, 2 * std::numbers::sqrt2}),  // z ≤ 2√2
    case_name);

// Euler and midpoint grow for every h: the energy ratio after n steps is exactly the
// theory's per-step factor to the n-th power (the update is a scaled rotation of
// (x, v/ω), so this holds for every step, not only asymptotically).
void check_growth(Integrator integrator, double z, double per_step_factor, bool grows = true) {
  const long n = 1000;
  const double h = z / kOmega;
  motus::Simulation sim(motus_test::oscillator(kOmega), integrator);
  const double e0 = sim.energy()->total;
  sim.advance(static_cast<double>(n) * h, h, motus::Tolerance{});
  ASSERT_EQ(sim.steps(), n);
  const double ratio = sim.energy()->total / e0;
  const double expected = std::pow(per_step_factor, static_cast<double>(n));
  std::printf("  %-8s z = %-5g energy ratio after %ld steps = %.15g (theory %.15g)\n", motus::info(integrator).name,
              z, n, ratio, expected);
  if (grows)
    EXPECT_GT(ratio, 1);
  else
    EXPECT_LT(ratio, 1);
  // Relative agreement limited only by rounding over 1000 steps.
  EXPECT_NEAR(ratio / expected, 1, 1e-11);
}

TEST(Unstable, EulerEnergyGrowsByOnePlusZSquared) {
  for (double z : {0.01, 0.1, 1.0}) check_growth(Integrator::Euler, z, 1 + z * z);  // integrators.md
}

TEST(Unstable, MidpointEnergyGrowsByOnePlusZFourthOverFour) {
  for (double z : {0.01, 0.1, 1.0}) check_growth(Integrator::Midpoint, z, 1 + std::pow(z, 4) / 4);  // integrators.md
}

TEST(Stable, Rk4EnergyShrinksByItsStabilityFunction) {
  // integrators.md: |R|² = 1 − z⁶/72 + z⁸/576 < 1 for 0 < z < 2√2.
  for (double z : {0.5, 1.0, 2.0, 2.8}) check_growth(Integrator::Rk4, z, 1 - std::pow(z, 6) / 72 + std::pow(z, 8) / 576, false);
}

}  // namespace
