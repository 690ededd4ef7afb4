// Explicit Euler on the course's spring reproduces the course's table exactly.
// Source: tests/reference/integrators.md ("The course's spring"; docs/course.md,
// section 2): m = 10, k = 5, x0 = 20, v0 = 0,
// h = 1; t = 0…5: x = 20, 20, 10, −10, −35, −55; v = 0, −10, −20, −25, −20, −2.5;
// a = −10, −10, −5, 5, 17.5, 27.5. Every one of these is exact in binary floating point.
#include <gtest/gtest.h>

#include <vector>

#include "test_scenes.hpp"

namespace {

TEST(EulerTable, ReproducesTheNotesSpringTableExactly) {
  // integrators.md, "The course's spring" (the course prints a(4), a(5) and v(5) rounded).
  const std::vector<double> x_expected = {20, 20, 10, -10, -35, -55};
  const std::vector<double> v_expected = {0, -10, -20, -25, -20, -2.5};
  const std::vector<double> a_expected = {-10, -10, -5, 5, 17.5, 27.5};

  motus::Simulation sim(motus_test::spring(10, 5, 20, 0), motus::Integrator::Euler);
  std::vector<double> x = {sim.state()[0]}, v = {sim.state()[1]}, t = {sim.time()};
  sim.advance(5, 1, motus::Tolerance{}, [&](const motus::Simulation& s) {
    t.push_back(s.time());
    x.push_back(s.state()[0]);
    v.push_back(s.state()[1]);
  });
  ASSERT_EQ(sim.steps(), 5);
  ASSERT_EQ(x.size(), 6u);
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(t[i], static_cast<double>(i));
    EXPECT_EQ(x[i], x_expected[i]) << "x at t = " << i;
    EXPECT_EQ(v[i], v_expected[i]) << "v at t = " << i;
    // a = F/m = −k x / m, computed by the engine's own force code.
    motus::Vector a(1);
    const motus::Vector xi = motus::Vector::Constant(1, x[i]), vi = motus::Vector::Constant(1, v[i]);
    sim.mechanical_system()->acceleration(static_cast<double>(i), xi, vi, a);
    EXPECT_EQ(a[0], a_expected[i]) << "a at t = " << i;
  }
}

TEST(EulerTable, EnergyGrowsByOnePlusOmegaSquaredHSquaredEachStep) {
  // integrators.md, stability table: Euler's energy grows by (1 + z²) each step;
  // here ω² = k/m = 1/2, h = 1, so by 3/2 — also exact in binary.
  motus::Simulation sim(motus_test::spring(10, 5, 20, 0), motus::Integrator::Euler);
  double previous = sim.energy()->total;
  EXPECT_EQ(previous, 1000.0);  // ½ k x0² = ½·5·400
  sim.advance(5, 1, motus::Tolerance{}, [&](const motus::Simulation& s) {
    const double e = s.energy()->total;
    EXPECT_DOUBLE_EQ(e / previous, 1.5);  // 1 + ω²h² = 1 + 0.5
    previous = e;
  });
}

}  // namespace
