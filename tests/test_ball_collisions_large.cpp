// The ball gas on a big grid: more than 2^17 cells (about 2.1 per ball in 2-D and 2.7 in 3-D
// at the first build, so from 90,000 and 64,000 balls), where the broad phase counting-sorts
// the grid in two levels (neighbour_lists.cpp, build_grid), and more than 2^14 balls, where
// the pair search and the events fetch ahead from memory (the box below has 20,000: fewer
// than 2^17 cells, but its fast balls make it slow to run). Checked against conservation
// (no forces: kinetic energy is kept by every elastic impulse, with balls and with the
// walls, to rounding; momentum too when there are no walls) and geometry (no contact
// missed: no two balls overlap, and nothing is outside its box, at the end).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>
#include <vector>

#include "motus/ball_lattice.hpp"
#include "motus/simulation.hpp"

namespace {

using motus::Integrator;
using motus::SceneDescription;
using motus::Simulation;

SceneDescription open_gas(int dimensions, long count, bool container = false) {
  SceneDescription scene;
  motus::MechanicalDescription m;
  m.dimensions = dimensions;
  motus::BallLattice lattice;  // radius 0.5, spacing 2
  lattice.count = count;
  lattice.container = container;
  motus::add_ball_lattice(m, lattice);
  scene.mechanical = std::move(m);
  scene.integrator = "symplectic-euler";
  scene.dt = 1.0 / 60;
  return scene;
}

// The smallest distance between two ball centres (points, of radius 0, do not count), by
// a sweep along x.
double closest_pair(const Simulation& sim) {
  const int d = sim.mechanical_system()->dimensions(), n = sim.mechanical_system()->size() / d;  // (size: coordinates)
  const auto& y = sim.state();
  std::vector<int> order;
  for (int i = 0; i < n; ++i)
    if (sim.scene().mechanical->bodies[static_cast<size_t>(i)].radius > 0) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return y[a * d] < y[b * d]; });
  double best = INFINITY;
  for (size_t a = 0; a < order.size(); ++a)
    for (size_t b = a + 1; b < order.size() && y[order[b] * d] - y[order[a] * d] < best; ++b) {
      double s = 0;
      for (int k = 0; k < d; ++k) s += std::pow(y[order[b] * d + k] - y[order[a] * d + k], 2);
      best = std::min(best, std::sqrt(s));
    }
  return best;
}

// A second of the open gas (no walls): thousands of contacts, so the checks say something.
void expect_gas_keeps_momentum_and_energy_and_misses_no_contact(const SceneDescription& scene, int d, long count) {
  Simulation sim(scene, Integrator::SymplecticEuler);
  const int n = sim.mechanical_system()->size();  // coordinates: N·d
  auto momentum = [&] {
    std::vector<double> p(static_cast<size_t>(d), 0.0);
    for (int i = 0; i < n; ++i) p[static_cast<size_t>(i % d)] += sim.state()[n + i];  // unit masses
    return p;
  };
  const std::vector<double> p0 = momentum();
  const double e0 = sim.energy()->total;
  sim.advance(60 * scene.dt, scene.dt, {});
  EXPECT_GT(sim.world()->collision_counters().ball_collisions, count / 20) << d << "-D";
  EXPECT_NEAR(sim.energy()->total, e0, 1e-12 * e0) << d << "-D";
  const std::vector<double> p1 = momentum();
  for (int k = 0; k < d; ++k) EXPECT_NEAR(p1[static_cast<size_t>(k)], p0[static_cast<size_t>(k)], 1e-9) << d << "-D";
  EXPECT_GE(closest_pair(sim), 1.0 - 1e-9) << d << "-D: two balls of radius 0.5 overlap (a contact was missed)";
}

TEST(BigGrid, KeepsMomentumAndEnergyAndMissesNoContact) {
  for (const auto& [d, count] : {std::pair{2, 90000L}, std::pair{3, 64000L}})
    expect_gas_keeps_momentum_and_energy_and_misses_no_contact(open_gas(d, count), d, count);
}

// With the balls' numbers in no order at all (a scene that lists its balls at random): no
// pass over the balls by number goes through space in order, and the same checks hold.
TEST(BigGrid, NumberedAtRandomKeepsMomentumAndEnergyAndMissesNoContact) {
  for (const auto& [d, count] : {std::pair{2, 90000L}, std::pair{3, 64000L}}) {
    SceneDescription scene = open_gas(d, count);
    motus::shuffle_bodies(scene.mechanical->bodies, 11);
    expect_gas_keeps_momentum_and_energy_and_misses_no_contact(scene, d, count);
  }
}

}  // namespace

namespace {

// In its box, with points (radius 0: they meet the walls, not the balls) and fast balls (that
// cross several cells in a step and search along their paths) among the balls.
TEST(BigGrid, InABoxWithPointsAndFastBallsKeepsEnergyAndEveryoneInside) {
  for (const auto& [d, count] : {std::pair{2, 20000L}, std::pair{3, 20000L}}) {
    SceneDescription scene = open_gas(d, count, true);
    auto& bodies = scene.mechanical->bodies;
    for (size_t i = 0; i < bodies.size(); i += 97) bodies[i].radius = 0;
    for (size_t i = 50; i < bodies.size(); i += 101)
      for (double& u : bodies[i].velocity) u *= 80;  // up to ~1.3 m a step: more than a radius
    Simulation sim(scene, Integrator::SymplecticEuler);
    const double e0 = sim.energy()->total;
    sim.advance(60 * scene.dt, scene.dt, {});
    const auto& counters = sim.world()->collision_counters();
    EXPECT_GT(counters.ball_collisions, count / 20) << d << "-D";
    EXPECT_GT(counters.wall_collisions, 100) << d << "-D";
    EXPECT_NEAR(sim.energy()->total, e0, 1e-12 * e0) << d << "-D";
    EXPECT_GE(closest_pair(sim), 1.0 - 1e-9) << d << "-D: two balls of radius 0.5 overlap (a contact was missed)";
    const auto& box = scene.mechanical->colliders.boxes.at(0);
    double deepest = 0;  // how far any body is inside a wall (its centre closer than r to a face)
    for (size_t i = 0; i < bodies.size(); ++i)
      for (int k = 0; k < d; ++k) {
        const double p = sim.state()[static_cast<Eigen::Index>(i) * d + k], r = bodies[i].radius;
        deepest = std::max({deepest, box.min[k] + r - p, p - (box.max[k] - r)});
      }
    EXPECT_LE(deepest, 1e-9) << d << "-D: a body went through a wall";
  }
}

}  // namespace
