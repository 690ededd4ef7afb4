// bench_collisions: the ball gas of issue 3 and docs/peers.md — balls of
// radius 0.5 on a square lattice of spacing 2, velocities uniform in [−1, 1]², no
// gravity, e = 1 with each other and the walls, dt = 1/60 — at N = 1,000, 10,000 and
// 100,000: ns per ball-step, and the relative energy change after 600 steps.
// Also: the course's spring stepped through the full world (motus::Simulation) against
// the bare symplectic-Euler loop on the same system (target: within 1.10x).
//
//   build/bench/bench_collisions [--benchmark_filter=BallGas]
#include <benchmark/benchmark.h>

#include <cmath>

#include "motus/ball_lattice.hpp"
#include "motus/integrate/symplectic_euler.hpp"
#include "motus/simulation.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;

SceneDescription ball_gas(long count, int dimensions) {
  SceneDescription scene;
  MechanicalDescription m;
  m.dimensions = dimensions;
  BallLattice lattice;
  lattice.count = count;
  add_ball_lattice(m, lattice);
  scene.mechanical = m;
  scene.integrator = "symplectic-euler";
  scene.dt = 1.0 / 60;
  return scene;
}

void BallGas(benchmark::State& state, int dimensions) {
  const long n = state.range(0);
  const SceneDescription scene = ball_gas(n, dimensions);
  Simulation sim(scene, Integrator::SymplecticEuler);
  const double e0 = sim.energy()->total;
  long steps = 0;
  for (auto _ : state) {
    sim.advance(sim.time() + scene.dt, scene.dt, {});
    ++steps;
  }
  // The energy change after 600 steps, from a fresh run (outside the timing).
  Simulation check(scene, Integrator::SymplecticEuler);
  check.advance(600 * scene.dt, scene.dt, {});
  state.counters["ns_per_ball_step"] =
      benchmark::Counter(static_cast<double>(steps * n), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["energy_change_600"] = (check.energy()->total - e0) / e0;
  state.counters["collisions_per_step"] =
      static_cast<double>(check.world()->collision_counters().ball_collisions) / 600.0;
}
BENCHMARK_CAPTURE(BallGas, 2d, 2)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BallGas, 3d, 3)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

// The course's spring (m = 10, k = 5) with symplectic Euler: the bare integrator on the
// system, and the same steps through Simulation and its World (which adds no pass).
SceneDescription notes_spring() {
  SceneDescription scene;
  MechanicalDescription m;
  m.dimensions = 1;
  m.bodies.push_back({10, {20}, {0}});
  Spring s;
  s.stiffness = 5;
  m.forces.springs.push_back(s);
  scene.mechanical = m;
  scene.dt = 0.01;
  return scene;
}
constexpr long kSpringSteps = 1000;

void SpringBareIntegrator(benchmark::State& state) {
  const SceneDescription scene = notes_spring();
  MechanicalSystem system(1, {10.0}, scene.mechanical->forces);
  Vector x(1), v(1);
  x << 20;
  v << 0;
  SymplecticEuler stepper;
  stepper.resize(1);
  double t = 0;
  for (auto _ : state) {
    for (long i = 0; i < kSpringSteps; ++i) {
      stepper.step(system, t, 0.01, x, v);
      t += 0.01;
    }
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(SpringBareIntegrator);

void SpringThroughWorld(benchmark::State& state) {
  Simulation sim(notes_spring(), Integrator::SymplecticEuler);
  for (auto _ : state) sim.advance(sim.time() + kSpringSteps * 0.01, 0.01, {});
}
BENCHMARK(SpringThroughWorld);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  motus::bench::RatioReporter reporter;
  reporter.add_ratio("spring through the full world / bare integrator (target <= 1.10)", "SpringThroughWorld",
                     "SpringBareIntegrator");
  reporter.add_ratio("ball gas 2-D: per-ball cost at 100,000 / at 1,000 (target <= 1.3)", "BallGas/2d/100000",
                     "BallGas/2d/1000", 100);
  reporter.add_ratio("ball gas 2-D: per-ball cost at 10,000 / at 1,000", "BallGas/2d/10000", "BallGas/2d/1000", 10);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
