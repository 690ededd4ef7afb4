// Measured global order at a fixed end time, halving h three times (four step sizes,
// three measured orders per method), on the oscillator x'' = −ω²x and on Kepler.
// Source of the expected orders: tests/reference/integrators.md, "Orders" table:
// euler 1, symplectic-euler 1, symplectic-euler-x 1, midpoint 2, verlet 2 (Taylor
// start), velocity-verlet 2, rk4 4, yoshida4 4. Each measured order must be within
// ±0.15 of it (the tolerance).
// Error = max-norm of the full state [x; v] minus the exact solution
// (motus::exact_state: "harmonic" / "kepler" via kepler_orbit) at the end time.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "motus/integrate/integrator_catalog.hpp"
#include "test_scenes.hpp"

namespace {

using motus::Integrator;

struct OrderCase {
  Integrator integrator;
  int expected_order;  // integrators.md
  long first_steps;    // number of steps for the largest h; then ×2, ×4, ×8
};

void check_orders(const motus::SceneDescription& scene, double end, const OrderCase& c) {
  double previous = 0;
  for (int k = 0; k < 4; ++k) {
    const long n = c.first_steps << k;
    const double error = motus_test::fixed_step_error(scene, c.integrator, end, n);
    if (k > 0) {
      const double order = std::log2(previous / error);
      std::printf("  %-20s h = %-10.4g error = %-10.3e measured order = %.4f\n", motus::info(c.integrator).name,
                  end / static_cast<double>(n), error, order);
      // integrators.md, "Orders": global order p, within ±0.15 (the issue).
      EXPECT_NEAR(order, c.expected_order, 0.15)
          << motus::info(c.integrator).name << " from h = " << end / static_cast<double>(n / 2) << " to h = "
          << end / static_cast<double>(n);
    }
    previous = error;
  }
}

class OscillatorOrder : public ::testing::TestWithParam<OrderCase> {};
class KeplerOrder : public ::testing::TestWithParam<OrderCase> {};

// x'' = −x (ω = 1) from (1, 0) to T = 10; exact: x = cos t, v = −sin t.
TEST_P(OscillatorOrder, MatchesTheory) { check_orders(motus_test::oscillator(1), 10, GetParam()); }

// Kepler (integrators.md) to T = 5, about 0.8 of an orbit — deliberately not a whole
// period. At T = 2π the symplectic Eulers measure order 2, not 1 (measured: 2.0000):
// n steps of symplectic Euler are velocity Verlet conjugated by a half kick,
// SE^n = K(−h/2) ∘ VV^n ∘ K(h/2), and the O(h) half kick at periapsis, (0, (h/2) a0),
// is perpendicular to v0, so it leaves H (hence the period) unchanged; the period map
// is the identity on the energy surface, so after exactly one orbit the final
// K(−h/2) cancels it to O(h²). A property of that end time, not of the integrators.
TEST_P(KeplerOrder, MatchesTheory) { check_orders(motus_test::kepler(), 5, GetParam()); }

// With a force of the velocity (a damper), the orders of the Verlet family and of Yoshida's
// composition are lost: velocity Verlet takes a_{n+1} = a(x_{n+1}, v_{n+½}), half a step's change
// of v away from a(x_{n+1}, v_{n+1}), an O(h) error in the acceleration that the last half kick
// carries into v as h/2 × c × O(h): a local error O(h²), so global order 1, whatever order the
// method has for forces of the positions alone (Störmer Verlet and the composition alike). The
// Runge–Kutta methods treat v as they treat x and keep theirs. docs/course.md says so; this
// measures it on the damped_spring scene (m = 1, k = 4, c = 0.4; exact: the damped harmonic
// solution) to T = 10.
class DampedOrder : public ::testing::TestWithParam<OrderCase> {};

TEST_P(DampedOrder, MatchesTheory) {
  motus::SceneDescription scene = motus_test::spring(1, 4, 1, 0);
  scene.mechanical->forces.springs[0].damping = 0.4;
  check_orders(scene, 10, GetParam());
}

std::string case_name(const ::testing::TestParamInfo<OrderCase>& info) {
  std::string name = motus::info(info.param.integrator).name;
  for (char& ch : name)
    if (ch == '-') ch = '_';
  return name;
}

// Step counts: largest h first; chosen in the asymptotic regime and above roundoff.
INSTANTIATE_TEST_SUITE_P(AllFixedStep, OscillatorOrder,
                         ::testing::Values(OrderCase{Integrator::Euler, 1, 10000},         // h = 1e-3 … 1.25e-4
                                           OrderCase{Integrator::SymplecticEuler, 1, 1000},  // h = 1e-2 …
                                           OrderCase{Integrator::SymplecticEulerX, 1, 1000},
                                           OrderCase{Integrator::Midpoint, 2, 1000},
                                           OrderCase{Integrator::Verlet, 2, 1000},
                                           OrderCase{Integrator::VelocityVerlet, 2, 1000},
                                           OrderCase{Integrator::Rk4, 4, 100},        // h = 0.1 … 0.0125
                                           OrderCase{Integrator::Yoshida4, 4, 100}),
                         case_name);

INSTANTIATE_TEST_SUITE_P(AllFixedStep, KeplerOrder,
                         ::testing::Values(OrderCase{Integrator::Euler, 1, 1000000},  // h = 5e-6 …
                                           OrderCase{Integrator::SymplecticEuler, 1, 100000},  // h = 5e-5 …
                                           OrderCase{Integrator::SymplecticEulerX, 1, 100000},
                                           OrderCase{Integrator::Midpoint, 2, 5000},  // h = 1e-3 …
                                           OrderCase{Integrator::Verlet, 2, 5000},  // (position Verlet's roundoff shows below ~1e-4)
                                           OrderCase{Integrator::VelocityVerlet, 2, 5000},
                                           OrderCase{Integrator::Rk4, 4, 500},  // h = 0.01 …
                                           OrderCase{Integrator::Yoshida4, 4, 500}),
                         case_name);

INSTANTIATE_TEST_SUITE_P(VelocityDependentForce, DampedOrder,
                         ::testing::Values(OrderCase{Integrator::SymplecticEuler, 1, 1000},  // h = 1e-2 …
                                           OrderCase{Integrator::Verlet, 1, 1000},
                                           OrderCase{Integrator::VelocityVerlet, 1, 1000},
                                           OrderCase{Integrator::Yoshida4, 1, 1000},
                                           OrderCase{Integrator::Midpoint, 2, 1000},
                                           OrderCase{Integrator::Rk4, 4, 100}),  // h = 0.1 …
                         case_name);

}  // namespace
