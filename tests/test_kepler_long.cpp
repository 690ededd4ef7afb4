// Kepler (μ = 1, q0 = (0.4, 0), p0 = (0, 2), H0 = −0.5, period 2π) over 1000 orbits.
// Source: tests/reference/integrators.md, "Test problems — Kepler": over 200 periods
// max |ΔH| is about 1.5e-2 (h = 0.01) for symplectic Euler and 3.7e-4 (h = 0.01) for
// velocity Verlet, and stays bounded; RK4's grows linearly in time; explicit Euler's
// orbit escapes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "motus/integrate/integrator_catalog.hpp"
#include "test_scenes.hpp"

namespace {

using motus::Integrator;
using motus_test::kKeplerEnergy;
using motus_test::kKeplerPeriod;

constexpr int kOrbits = 1000;
constexpr double kH = 0.01;  // integrators.md quotes its figures at h = 0.01

// max |H − H0| within each orbit k (t in [k T, (k+1) T)), and |H − H0| at the end.
struct EnergyHistory {
  std::vector<double> per_orbit;
  double final_error = 0;

  double max_over(int first, int last) const {  // orbits [first, last)
    return *std::max_element(per_orbit.begin() + first, per_orbit.begin() + last);
  }
};

EnergyHistory run(Integrator integrator) {
  EnergyHistory history;
  history.per_orbit.assign(kOrbits + 1, 0.0);
  motus::Simulation sim(motus_test::kepler(), integrator);
  EXPECT_DOUBLE_EQ(sim.energy()->total, kKeplerEnergy);  // integrators.md: H0 = −0.5
  sim.advance(kOrbits * kKeplerPeriod, kH, motus::Tolerance{}, [&](const motus::Simulation& s) {
    const int orbit = std::min(kOrbits, static_cast<int>(s.time() / kKeplerPeriod));
    const double error = std::abs(s.energy()->total - kKeplerEnergy);
    history.per_orbit[static_cast<size_t>(orbit)] = std::max(history.per_orbit[static_cast<size_t>(orbit)], error);
    history.final_error = error;
  });
  return history;
}

struct BoundedCase {
  Integrator integrator;
  double figure_200_orbits;  // integrators.md's max |ΔH| over 200 periods at h = 0.01 (0: none quoted)
};

class SymplecticKepler : public ::testing::TestWithParam<BoundedCase> {};

TEST_P(SymplecticKepler, EnergyErrorStaysBounded) {
  const auto c = GetParam();
  const EnergyHistory history = run(c.integrator);
  const double first100 = history.max_over(0, 100), last100 = history.max_over(kOrbits - 100, kOrbits);
  const double first200 = history.max_over(0, 200);
  std::printf("  %-20s max|dH| first 200 orbits %.4e, first 100 %.4e, last 100 %.4e (ratio %.4f)\n",
              motus::info(c.integrator).name, first200, first100, last100, last100 / first100);
  // integrators.md: "stays bounded" — no growth from the first 100 orbits to the last
  // 100 beyond a small factor (1.5; a drift linear in time would give ~10).
  EXPECT_LT(last100 / first100, 1.5);
  EXPECT_LT(history.max_over(0, kOrbits), 1.5 * first100);
  if (c.figure_200_orbits > 0) {
    // integrators.md quotes four significant digits (its script's): agree to half a unit of the last one.
    const double half_unit = 0.0005 * std::pow(10.0, std::floor(std::log10(c.figure_200_orbits)));
    EXPECT_NEAR(first200, c.figure_200_orbits, half_unit);
  }
}

std::string case_name(const ::testing::TestParamInfo<BoundedCase>& info) {
  std::string name = motus::info(info.param.integrator).name;
  for (char& ch : name)
    if (ch == '-') ch = '_';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Symplectic, SymplecticKepler,
                         ::testing::Values(BoundedCase{Integrator::SymplecticEuler, 1.459e-2},  // integrators.md
                                           BoundedCase{Integrator::VelocityVerlet, 3.707e-4},   // integrators.md
                                           BoundedCase{Integrator::SymplecticEulerX, 0},
                                           BoundedCase{Integrator::Verlet, 0},
                                           BoundedCase{Integrator::Yoshida4, 0}),
                         case_name);

TEST(Rk4Kepler, EnergyErrorGrowsLinearly) {
  // integrators.md: "RK4's grows linearly in time".
  const EnergyHistory history = run(Integrator::Rk4);
  const double after100 = history.per_orbit[99], after1000 = history.final_error;
  std::printf("  rk4 |dH| in orbit 100 %.4e, at orbit 1000 %.4e (ratio %.3f; linear: 10)\n", after100, after1000,
              after1000 / after100);
  // Linear growth makes the ratio 10 (1000 orbits / 100); "roughly": within a factor 2.
  EXPECT_GT(after1000 / after100, 5);
  EXPECT_LT(after1000 / after100, 20);
}

TEST(EulerKepler, OrbitEscapes) {
  // integrators.md: "explicit Euler's orbit escapes" — its energy rises to H ≥ 0 (unbound).
  motus::Simulation sim(motus_test::kepler(), Integrator::Euler);
  bool escaped = false;
  int orbit = 0;
  for (; orbit < kOrbits && !escaped; ++orbit) {
    sim.advance((orbit + 1) * kKeplerPeriod, kH, motus::Tolerance{});
    escaped = !(sim.energy()->total < 0);
  }
  const double r = std::hypot(sim.state()[0], sim.state()[1]);
  std::printf("  euler: H = %.4g after %d orbits' time, r = %.4g\n", sim.energy()->total, orbit, r);
  EXPECT_TRUE(escaped);
}

}  // namespace
