// The adaptive integrators (rk45 = Dormand–Prince 5(4), rk4-doubling = RK4 by step
// doubling) on Kepler (tests/reference/integrators.md: μ = 1, q0 = (0.4, 0), p0 = (0, 2), e = 0.6,
// period 2π; exact solution motus::kepler_orbit) over one orbit, rtol = atol = tol,
// tol = 1e-6 … 1e-10, first step 0.01.
//
// What is checked:
//  1. Local error (the controller's contract, integrators.md "Step-size control":
//     accept a step when err ≤ 1, err = √(mean_i (e_i/sc_i)²), sc_i = atol + rtol·
//     max(|y0_i|, |y1_i|)): with e = the TRUE local error of each accepted step (the
//     result minus the exact solution started from the step's start), err ≤ 1. Both
//     methods go on with the more accurate of the two results they compare (rk45 the
//     fifth-order one, rk4-doubling the two half steps), whose true error is below the
//     estimate the controller holds to 1 (measured: 0.34 for rk45, 0.80 for rk4-doubling).
//  2. Fewer derivative evaluations (Simulation::evaluations(), rejected attempts
//     included) than fixed-step RK4 needs for the same final global error (the issue).
//  3. rk45 agrees with an independent implementation, SciPy's solve_ivp RK45
//     (tests/reference/scipy_rk45_kepler.py and its recorded output).
//  4. DISABLED — the "final global error within 10 × tol" (global error =
//     max-norm of [x; v] minus the exact state at t = 2π). It does not hold, for the
//     engine nor for SciPy (item 3): the measured error/tol is 390–840 for rk45 and
//     360–710 for rk4-doubling. Local error control bounds each step's error, not the
//     global one; on Kepler an energy error made near periapsis turns into a phase
//     error that grows along the orbit. Kept so that the claim stays visible; run it
//     with --gtest_also_run_disabled_tests.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

#include "motus/exact/kepler_orbit.hpp"
#include "motus/integrate/integrator_catalog.hpp"
#include "test_scenes.hpp"

namespace {

using motus::Integrator;
using motus_test::kKeplerPeriod;

constexpr std::array<double, 5> kTolerances = {1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
constexpr double kFirstStep = 0.01;

struct Outcome {
  double error = 0;             // global: max-norm at the end vs exact
  double worst_local = 0;       // max over accepted steps of the scaled true local error
  long evaluations = 0, steps = 0, rejected = 0;
};

Outcome adaptive(Integrator integrator, double tol) {
  Outcome out;
  motus::Simulation sim(motus_test::kepler(), integrator);
  motus::Vector previous = sim.state();
  double previous_t = sim.time();
  sim.advance(kKeplerPeriod, kFirstStep, motus::Tolerance{tol, tol}, [&](const motus::Simulation& s) {
    const motus::Vector& y = s.state();
    const motus::KeplerState exact =
        motus::kepler_orbit({previous[0], previous[1]}, {previous[2], previous[3]}, 1, s.time() - previous_t);
    const double e[4] = {y[0] - exact.x[0], y[1] - exact.x[1], y[2] - exact.v[0], y[3] - exact.v[1]};
    double sum = 0;
    for (int i = 0; i < 4; ++i) {
      const double sc = tol + tol * std::max(std::abs(previous[i]), std::abs(y[i]));  // integrators.md
      sum += (e[i] / sc) * (e[i] / sc);
    }
    out.worst_local = std::max(out.worst_local, std::sqrt(sum / 4));
    previous = y;
    previous_t = s.time();
  });
  EXPECT_EQ(sim.time(), kKeplerPeriod);  // adaptive runs land exactly on the end time
  out.error = motus_test::error_vs_exact(sim);
  out.evaluations = sim.evaluations();
  out.steps = sim.steps();
  out.rejected = sim.rejected();
  return out;
}

// The fewest evaluations fixed-step RK4 needs to reach a final error ≤ target: the
// smallest step count (searched in 2% increments) whose error is ≤ target.
Outcome rk4_matching(double target) {
  for (double n = 16;; n *= 1.02) {
    const long steps = std::lround(n);
    motus::Simulation sim(motus_test::kepler(), Integrator::Rk4);
    sim.advance(kKeplerPeriod, kKeplerPeriod / static_cast<double>(steps), motus::Tolerance{});
    Outcome out;
    out.error = motus_test::error_vs_exact(sim);
    out.evaluations = sim.evaluations();
    out.steps = sim.steps();
    if (out.error <= target || steps > 10000000) return out;
  }
}

std::string name_of(const ::testing::TestParamInfo<Integrator>& info) {
  return info.param == Integrator::Rk45 ? std::string("rk45") : std::string("rk4_doubling");
}

class Adaptive : public ::testing::TestWithParam<Integrator> {};

TEST_P(Adaptive, TrueLocalErrorWithinTolerance) {
  for (double tol : kTolerances) {
    const Outcome a = adaptive(GetParam(), tol);
    std::printf("  %-12s tol %.0e: worst scaled true local error %.3g; %ld steps, %ld rejected; global error %.3e"
                " (error/tol %.0f)\n",
                motus::info(GetParam()).name, tol, a.worst_local, a.steps, a.rejected, a.error, a.error / tol);
    EXPECT_LE(a.worst_local, 1) << "tol = " << tol;  // integrators.md: a step is accepted when err ≤ 1
  }
}

TEST_P(Adaptive, FewerEvaluationsThanFixedStepRk4ForTheSameError) {
  for (double tol : kTolerances) {
    const Outcome a = adaptive(GetParam(), tol);
    const Outcome f = rk4_matching(a.error);
    std::printf("  %-12s tol %.0e: error %.3e with %ld evaluations; fixed-step rk4: %ld steps, error %.3e, %ld"
                " evaluations\n",
                motus::info(GetParam()).name, tol, a.error, a.evaluations, f.steps, f.error, f.evaluations);
    EXPECT_LT(a.evaluations, f.evaluations) << "tol = " << tol;  // the issue
  }
}

// See item 4 above: fails (error/tol 360–840); disabled, reported.
TEST_P(Adaptive, DISABLED_GlobalErrorWithinTenTimesTolerance) {
  for (double tol : kTolerances) {
    const Outcome a = adaptive(GetParam(), tol);
    EXPECT_LE(a.error, 10 * tol) << "tol = " << tol << ": error " << a.error;  // the issue
  }
}

INSTANTIATE_TEST_SUITE_P(Kepler, Adaptive, ::testing::Values(Integrator::Rk45, Integrator::Rk4Doubling), name_of);

TEST(Rk45, MatchesScipySolveIvpRk45) {
  // tests/reference/README.md: SciPy 1.10.1 solve_ivp(RK45), same problem and settings, with
  // SciPy's cap on a step's growth (10) set to motus's (5, step_size_control.hpp).
  struct ScipyRow {
    double tol, error;
    long nfev, steps;
  };
  constexpr std::array<ScipyRow, 5> scipy = {{{1e-6, 8.4333530085e-04, 253, 32},
                                              {1e-7, 7.8140532492e-05, 373, 49},
                                              {1e-8, 6.3726824955e-06, 463, 75},
                                              {1e-9, 4.9770190934e-07, 703, 117},
                                              {1e-10, 3.8905685614e-08, 1123, 186}}};
  for (const auto& row : scipy) {
    const Outcome a = adaptive(Integrator::Rk45, row.tol);
    // Same pair, same controller: the same steps and evaluations.
    EXPECT_EQ(a.evaluations, row.nfev) << "tol = " << row.tol;
    EXPECT_EQ(a.steps, row.steps) << "tol = " << row.tol;
    // The same global error but for rounding: the same arithmetic in another order, over at most
    // 186 steps of 6 stages on a state of size ≤ 4 (an ulp 9e-16), leaves the two ends within
    // 1e-12 (a thousand ulps; measured: 9e-14 at most), against errors of 3.9e-8 and more.
    EXPECT_NEAR(a.error, row.error, 1e-12) << "tol = " << row.tol;
  }
}

}  // namespace
