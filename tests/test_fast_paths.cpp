// The fast paths compute the same numbers as the general ones, to the last bit (the expected
// values are the general path's, measured in the same test):
//  1. One body (OneBodyAsFirstOrder<D>: the forces with loops whose bounds are known at compile
//     time, F in registers) against the general point-mass path (MechanicalAsFirstOrder): the
//     derivative at 200 states for every force law a one-body scene can have — uniform gravity, a
//     spring to an anchor (zero-length, with a rest length, with damping), linear drag (on every
//     body, on body 0), central gravity (softened, off the origin), the pendulum — each alone and
//     all together, in 1, 2 and 3 dimensions.
//  2. Simulation, which steps a system by its concrete type with stages of a size known at
//     compile time (systems/concrete_system.hpp), against the same integrator stepping the system
//     through the general interfaces (FirstOrderSystem's virtual derivative; MechanicalAsFirstOrder
//     with Vectors): the same final state, bit for bit, for rk4, rk45 and dop853 on Lorenz and on
//     Kepler.
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <random>

#include "motus/integrate/dop853.hpp"
#include "motus/integrate/rk4.hpp"
#include "motus/integrate/rk45.hpp"
#include "motus/systems/mechanical_as_first_order.hpp"
#include "test_scenes.hpp"

namespace {

using motus::Vector;

void expect_same_bits(const Vector& a, const Vector& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (Eigen::Index i = 0; i < a.size(); ++i)
    EXPECT_EQ(std::bit_cast<std::uint64_t>(a[i]), std::bit_cast<std::uint64_t>(b[i]))
        << what << ": entry " << i << ", " << a[i] << " against " << b[i];
}

motus::ForceSet one_of_each(int d) {
  motus::ForceSet f;
  f.gravity.push_back({{0.3, -9.81, 1.5}});
  motus::Spring zero_length;
  zero_length.stiffness = 5;
  zero_length.anchor = {0.5, -0.25, 0.125};
  f.springs.push_back(zero_length);
  motus::Spring with_length = zero_length;
  with_length.rest_length = 0.7;
  with_length.damping = 0.3;
  f.springs.push_back(with_length);
  f.drag.push_back({-1, 0.2});
  f.drag.push_back({0, 0.05});
  motus::CentralGravity centre;
  centre.mu = 2.5;
  centre.softening = 0.01;
  centre.centre = {0.1, 0.2, -0.3};
  f.central_gravity.push_back(centre);
  motus::CentralGravity plain;
  f.central_gravity.push_back(plain);
  if (d == 1) f.pendulums.push_back({0, 9.81, 1.5});
  return f;
}

// Each kind alone (one force set per kind of one_of_each), then all together.
std::vector<motus::ForceSet> force_sets(int d) {
  const motus::ForceSet all = one_of_each(d);
  std::vector<motus::ForceSet> sets;
  auto alone = [&](auto member) {
    motus::ForceSet s;
    s.*member = all.*member;
    if (!(s.*member).empty()) sets.push_back(s);
  };
  alone(&motus::ForceSet::gravity);
  alone(&motus::ForceSet::springs);
  alone(&motus::ForceSet::drag);
  alone(&motus::ForceSet::central_gravity);
  alone(&motus::ForceSet::pendulums);
  sets.push_back(all);
  return sets;
}

template <int D>
void one_body_matches_general_path() {
  std::mt19937_64 random(20240601 + D);
  std::uniform_real_distribution<double> value(-2, 2);
  for (const auto& forces : force_sets(D)) {
    motus::MechanicalSystem system(D, {1.7}, forces);
    motus::MechanicalAsFirstOrder general(system);
    motus::OneBodyAsFirstOrder<D> one(system);
    for (int k = 0; k < 200; ++k) {
      Vector y(2 * D), fast(2 * D), slow(2 * D);
      for (int i = 0; i < 2 * D; ++i) y[i] = value(random);
      one.derivative(0.5, y, fast);
      general.derivative(0.5, y, slow);
      expect_same_bits(fast, slow, "one body in " + std::to_string(D) + "-D");
    }
  }
}

TEST(FastPaths, OneBodyIsTheGeneralPointMassPathIn1D) { one_body_matches_general_path<1>(); }
TEST(FastPaths, OneBodyIsTheGeneralPointMassPathIn2D) { one_body_matches_general_path<2>(); }
TEST(FastPaths, OneBodyIsTheGeneralPointMassPathIn3D) { one_body_matches_general_path<3>(); }

// The general path by hand: the stepper on `system` (an interface or the general bridge), as
// Simulation::advance takes its steps.
template <class Stepper, class System>
Vector step_generally(System& system, Vector y, double end, double dt, bool adaptive) {
  Stepper stepper;
  stepper.resize(static_cast<int>(y.size()));
  double t = 0;
  if constexpr (requires { stepper.set_tolerance(motus::Tolerance{}); }) {
    stepper.set_tolerance({1e-10, 1e-10});
    double h = dt;
    while (adaptive && t < end) {
      double step = std::min(h, end - t);
      const bool landing = step < h;
      const bool accepted = stepper.try_step(system, t, step, y);
      if (!landing || !accepted) h = step;
      if (accepted && landing) t = end;
    }
  } else {
    const long n = motus::fixed_step_count(end, dt);
    for (long i = 0; i < n; ++i) {
      stepper.step(system, t, dt, y);
      t = static_cast<double>(i + 1) * dt;
    }
  }
  return y;
}

template <class Stepper>
void simulation_matches_general_path(motus::Integrator integrator, bool adaptive) {
  const auto lorenz = motus_test::first_order("lorenz", {1, 1, 1});
  motus::Simulation fast(lorenz, integrator);
  fast.advance(2, 1e-3, {1e-10, 1e-10});
  motus::Simulation owner(lorenz, integrator);
  motus::FirstOrderSystem& as_interface = *owner.first_order_system();  // a virtual call per evaluation
  expect_same_bits(fast.state(), step_generally<Stepper>(as_interface, owner.state(), 2, 1e-3, adaptive),
                   std::string("lorenz, ") + motus::info(integrator).name);

  const auto kepler = motus_test::kepler();
  motus::Simulation orbit(kepler, integrator);
  orbit.advance(motus_test::kKeplerPeriod, 0.01, {1e-10, 1e-10});
  motus::Simulation bodies(kepler, integrator);
  motus::MechanicalAsFirstOrder general(*bodies.mechanical_system());
  expect_same_bits(orbit.state(),
                   step_generally<Stepper>(general, bodies.state(), motus_test::kKeplerPeriod, 0.01, adaptive),
                   std::string("kepler, ") + motus::info(integrator).name);
}

TEST(FastPaths, SimulationIsTheGeneralPathForRk4) {
  simulation_matches_general_path<motus::Rk4>(motus::Integrator::Rk4, false);
}
TEST(FastPaths, SimulationIsTheGeneralPathForRk45) {
  simulation_matches_general_path<motus::Rk45>(motus::Integrator::Rk45, true);
}
TEST(FastPaths, SimulationIsTheGeneralPathForDop853) {
  simulation_matches_general_path<motus::Dop853>(motus::Integrator::Dop853, true);
}

}  // namespace
