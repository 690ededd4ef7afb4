// bench_collisions: the ball gas of issue 3 and docs/peers.md — balls of
// radius 0.5 on a square (cubic) lattice of spacing 2, velocities uniform in [−1, 1]^d, no
// gravity, e = 1 with each other and the walls, dt = 1/60 — at N = 10^3, 10^4, 10^5 and
// 10^6, in 2-D and 3-D: ns per ball-step, the neighbour lists' builds per step, and the
// relative energy change over a fresh run (the worst over the timed windows; and over 600
// steps at 10^4). Building the 10^6 scene (the lattice and the Simulation over it) is timed
// on its own, and the gas at 10^5 and 10^6 with its balls numbered at random (not row by row,
// as the lattice numbers them). The ratios at the end are issue 13's: per-ball cost at 10^6 /
// at 10^3 (target ≤ 1.3), 3-D / 2-D (target ≤ 1.5); and what numbering at random costs. Beside
// them, the gas at 10^3 and 10^6 timed over the same window after 10 s of running (a long
// run's cost, once the speeds have their tail), and the drift alone (x += h·v over the same
// balls, nothing else) at 10^3 and 10^6: what the memory alone charges a big gas per ball. And a million balls as a thousand (or a hundred)
// separate gases stepped in turn, K steps each: how much of that a step that took each region
// several steps ahead while it is in cache could win back, at best.
// Also: the course's spring stepped through the full world (motus::Simulation) against
// the bare symplectic-Euler loop on the same system (target: within 1.10x).
//
//   build/bench/bench_collisions [--benchmark_filter=BallGas/] [--benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true]   (the sizes in random order: a noisy
//       machine's slow spells then fall on all of them alike)
//   build/bench/bench_collisions --benchmark_filter='BallGas/(2d|3d)/(1000|1000000)/|BallGasInRegions'
//       --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true   (the regions)
//   build/bench/bench_collisions --benchmark_filter='BallGas/(2d|3d)/(1000|1000000)/|BallGasSettled'
//       --benchmark_repetitions=3   (the same window after 10 s of the gas: a long run's cost)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "motus/ball_lattice.hpp"
#include "motus/integrate/symplectic_euler.hpp"
#include "motus/simulation.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;

// (numbered_at_random: the same balls listed in a random order, so that a ball's number no
// longer tells where it is, as in a scene that lists its balls by hand or from a script.)
SceneDescription ball_gas(long count, int dimensions, bool numbered_at_random = false) {
  SceneDescription scene;
  MechanicalDescription m;
  m.dimensions = dimensions;
  BallLattice lattice;
  lattice.count = count;
  add_ball_lattice(m, lattice);
  if (numbered_at_random) shuffle_bodies(m.bodies, 11);
  scene.mechanical = std::move(m);
  scene.integrator = "symplectic-euler";
  scene.dt = 1.0 / 60;
  return scene;
}

// The thread's CPU time: the machine's two cores are shared, and under load the wall
// time of a step doubles while its CPU time holds still.
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// One iteration: a fresh gas, stepped once (which sizes the buffers), then kWindow
// steps timed. Every N is timed over the same stretch of simulated time, so that a
// ball meets as many others per step at every N (the lattice starts with no contact and
// takes seconds to reach its collision rate) and only N itself differs.
constexpr long kWindow = 120;

void BallGas(benchmark::State& state, int dimensions, bool numbered_at_random = false, long settle_steps = 0) {
  const long n = state.range(0);
  const SceneDescription scene = ball_gas(n, dimensions, numbered_at_random);
  double seconds = 0, worst_energy = 0, collisions = 0, builds = 0;
  long windows = 0;
  for (auto _ : state) {
    Simulation sim(scene, Integrator::SymplecticEuler);
    sim.advance(sim.time() + static_cast<double>(1 + settle_steps) * scene.dt, scene.dt, {});
    const double e0 = sim.energy()->total;
    const CollisionCounters before = sim.world()->collision_counters();
    const double start = thread_seconds();
    sim.advance(sim.time() + static_cast<double>(kWindow) * scene.dt, scene.dt, {});
    const double elapsed = thread_seconds() - start;
    state.SetIterationTime(elapsed);
    seconds += elapsed;
    ++windows;
    worst_energy = std::max(worst_energy, std::abs(sim.energy()->total - e0) / e0);
    const CollisionCounters after = sim.world()->collision_counters();
    collisions += static_cast<double>(after.ball_collisions - before.ball_collisions);
    builds += static_cast<double>(after.grid_builds - before.grid_builds);
  }
  const double ball_steps = static_cast<double>(windows * kWindow * n);
  state.counters["ns_per_ball_step"] = 1e9 * seconds / ball_steps;
  state.counters["collisions_per_ball_step"] = collisions / ball_steps;
  // How often the neighbour lists are built: their life is set by the fastest ball, and a
  // bigger gas has a faster one (its speeds' tail is longer), so it builds more often.
  state.counters["list_builds_per_step"] = builds / static_cast<double>(windows * kWindow);
  state.counters["energy_change"] = worst_energy;  // relative, over a window, the worst
}
// Manual time = the thread's CPU time over the window (see thread_seconds).
// With --benchmark_repetitions, the minimum beside the median (and the ratios of both).
double minimum(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }
BENCHMARK_CAPTURE(BallGas, 2d, 2)->RangeMultiplier(10)->Range(1000, 1000000)->UseManualTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);
BENCHMARK_CAPTURE(BallGas, 3d, 3)->RangeMultiplier(10)->Range(1000, 1000000)->UseManualTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);
// The lattice numbers its balls row by row, so that balls near in number are near in space,
// and so are the data the collisions read together. The same gas numbered at random shows what
// that order is worth: at 10^5 and 10^6 balls the data no longer fit in cache.
BENCHMARK_CAPTURE(BallGas, 2d_numbered_at_random, 2, true)->Arg(100000)->Arg(1000000)->UseManualTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);
BENCHMARK_CAPTURE(BallGas, 3d_numbered_at_random, 3, true)->Arg(100000)->Arg(1000000)->UseManualTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

// The same window after the gas has run for 10 s (600 steps, not timed): a fresh lattice's speeds
// are uniform in [−1, 1]^d, and the first seconds' collisions turn them into Maxwell's
// distribution, whose tail has no end. Then a ball meets a third more others per step, and a
// bigger gas has a faster fastest ball: its neighbour lists' half skin runs out sooner (their
// life is set by that ball) and they are built more often than a small gas's. Its balls have
// also wandered further from the lattice's numbering. What a long run of a big gas costs.
constexpr long kSettleSteps = 600;
void BallGasSettled(benchmark::State& state, int dimensions) { BallGas(state, dimensions, false, kSettleSteps); }
BENCHMARK_CAPTURE(BallGasSettled, 2d, 2)->Arg(1000)->Arg(1000000)->UseManualTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);
BENCHMARK_CAPTURE(BallGasSettled, 3d, 3)->Arg(1000)->Arg(1000000)->UseManualTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

// The least a step of the gas can do: every ball moved on by h·v, one pass over x and v and
// nothing else (no pair, no grid, no contact), over the same balls and the same 120 steps.
// What it costs more per ball at 10^6 than at 10^3 is what the machine's memory alone charges
// a million balls: at 10^3 the arrays are in the core's own cache, at 10^6 (32 MB in 2-D, 48 MB
// in 3-D) they stream from the shared one. Every step of the gas makes this pass (inside its
// pair pass), so that extra is part of the gas's own extra per ball too.
void BallGasDriftAlone(benchmark::State& state, int dimensions) {
  const long n = state.range(0);
  const SceneDescription scene = ball_gas(n, dimensions);
  // The gas's own start, [x; v], as Simulation lays it out for the step.
  const Vector initial = Simulation(scene, Integrator::SymplecticEuler).state();
  Vector x = initial.head(n * dimensions), v = initial.tail(n * dimensions);
  const double h = scene.dt;
  double seconds = 0;
  long windows = 0;
  for (auto _ : state) {
    const double start = thread_seconds();
    for (long step = 0; step < kWindow; ++step) {
      x += h * v;
      benchmark::ClobberMemory();  // (every step's pass is done, not folded into one)
    }
    const double elapsed = thread_seconds() - start;
    state.SetIterationTime(elapsed);
    seconds += elapsed;
    ++windows;
  }
  benchmark::DoNotOptimize(x.data());
  state.counters["ns_per_ball_step"] = 1e9 * seconds / static_cast<double>(windows * kWindow * n);
}
// (Registered in main as BallGas/2d_drift_alone and BallGas/3d_drift_alone, so that the gas's
// filter, BallGas/, runs them beside it.)

// A million balls as separate gases (regions) of 10^3 or 10^4 balls, stepped in turn: the best
// case for a step that works region by region, since these regions have no border (no ball
// crosses from one to the next, no contact joins two). Each region is taken on by K steps
// before the next one. K = 1 is region by region every step: each region's data come back
// from the shared cache every step. K = 8 or 24 keeps a region in the core's own cache for K
// steps in a row, as a step "blocked in time" would if it could take a region ahead of its
// neighbours. Compared per ball-step with one gas of 10^3 (always in cache) and one gas of 10^6:
// how far such a redesign of the step could at best bring the ratio of 10^6 to 10^3 down.
// Args: K, the balls in a region.
constexpr long kMillion = 1000000;

void BallGasInRegions(benchmark::State& state, int dimensions) {
  const long steps_per_region = state.range(0), region_balls = state.range(1);
  const SceneDescription scene = ball_gas(region_balls, dimensions);
  double seconds = 0;
  long windows = 0;
  for (auto _ : state) {
    std::vector<std::unique_ptr<Simulation>> regions;
    for (long r = 0; r < kMillion / region_balls; ++r) {
      regions.push_back(std::make_unique<Simulation>(scene, Integrator::SymplecticEuler));
      regions.back()->advance(regions.back()->time() + scene.dt, scene.dt, {});  // (as BallGas: buffers sized)
    }
    const double start = thread_seconds();
    for (long step = 0; step < kWindow; step += steps_per_region)
      for (auto& region : regions)
        region->advance(region->time() + static_cast<double>(steps_per_region) * scene.dt, scene.dt, {});
    const double elapsed = thread_seconds() - start;
    state.SetIterationTime(elapsed);
    seconds += elapsed;
    ++windows;
  }
  state.counters["ns_per_ball_step"] = 1e9 * seconds / static_cast<double>(windows * kWindow * kMillion);
}
// (Registered in main as BallGasInRegions/2d and /3d.)
constexpr std::pair<long, long> kRegionRuns[] = {{1, 1000}, {8, 1000}, {24, 1000}, {24, 10000}};
static_assert(std::ranges::all_of(kRegionRuns, [](const auto& run) {
                return kWindow % run.first == 0 && kMillion % run.second == 0;
              }),
              "every K divides the window, every region's balls a million");

// Energy over issue 3's 600 steps (not timed).
void BallGasEnergy600(benchmark::State& state, int dimensions) {
  const long n = state.range(0);
  const SceneDescription scene = ball_gas(n, dimensions);
  double change = 0;
  for (auto _ : state) {
    Simulation sim(scene, Integrator::SymplecticEuler);
    const double e0 = sim.energy()->total;
    sim.advance(600 * scene.dt, scene.dt, {});
    change = (sim.energy()->total - e0) / e0;
  }
  state.counters["energy_change_600"] = change;
}
BENCHMARK_CAPTURE(BallGasEnergy600, 2d, 2)->Arg(10000)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BallGasEnergy600, 3d, 3)->Arg(10000)->Iterations(1)->Unit(benchmark::kMillisecond);

// Building the scene: the lattice's description and the Simulation over it (what a run
// does before its first step).
void BallGasBuild(benchmark::State& state, int dimensions) {
  const long n = state.range(0);
  for (auto _ : state) {
    const double start = thread_seconds();
    auto scene = std::make_unique<SceneDescription>(ball_gas(n, dimensions));
    auto sim = std::make_unique<Simulation>(*scene, Integrator::SymplecticEuler);
    state.SetIterationTime(thread_seconds() - start);
    benchmark::DoNotOptimize(sim->time());  // (freed outside the timing)
  }
}
BENCHMARK_CAPTURE(BallGasBuild, 2d, 2)->Arg(1000000)->UseManualTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);
BENCHMARK_CAPTURE(BallGasBuild, 3d, 3)->Arg(1000000)->UseManualTime()->Unit(benchmark::kMillisecond)->ComputeStatistics("min", minimum);

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
  scene.mechanical = std::move(m);
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
BENCHMARK(SpringBareIntegrator)->ComputeStatistics("min", minimum);

void SpringThroughWorld(benchmark::State& state) {
  Simulation sim(notes_spring(), Integrator::SymplecticEuler);
  for (auto _ : state) sim.advance(sim.time() + kSpringSteps * 0.01, 0.01, {});
}
BENCHMARK(SpringThroughWorld)->ComputeStatistics("min", minimum);

}  // namespace

int main(int argc, char** argv) {
  for (const auto& [d, dimensions] : {std::pair{"2d", 2}, std::pair{"3d", 3}})
    benchmark::RegisterBenchmark((std::string("BallGas/") + d + "_drift_alone").c_str(), BallGasDriftAlone, dimensions)
        ->Arg(1000)
        ->Arg(1000000)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond)
        ->ComputeStatistics("min", minimum);
  for (const auto& [d, dimensions] : {std::pair{"2d", 2}, std::pair{"3d", 3}})
    for (const auto& [steps, balls] : kRegionRuns)
      benchmark::RegisterBenchmark((std::string("BallGasInRegions/") + d).c_str(), BallGasInRegions, dimensions)
          ->Args({steps, balls})
          ->UseManualTime()
          ->Unit(benchmark::kMillisecond)
          ->ComputeStatistics("min", minimum);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  motus::bench::RatioReporter reporter;
  reporter.add_ratio("spring through the full world / bare integrator (target <= 1.10)", "SpringThroughWorld",
                     "SpringBareIntegrator");
  // With --benchmark_repetitions each ratio is of the fastest repetitions, the medians' beside it.
  auto gas = [](const std::string& d, const char* n) { return "BallGas/" + d + "/" + n + "/manual_time"; };
  for (const std::string d : {"2d", "3d"}) {
    const std::string D = d == "2d" ? "2-D" : "3-D";
    reporter.add_ratio("ball gas " + D + ": per ball at 10^6 / at 10^3 (target <= 1.3)", gas(d, "1000000"),
                       gas(d, "1000"), 1000);
    reporter.add_ratio("ball gas " + D + ": per ball at 10^5 / at 10^3", gas(d, "100000"), gas(d, "1000"), 100);
    reporter.add_ratio("ball gas " + D + ": per ball at 10^4 / at 10^3", gas(d, "10000"), gas(d, "1000"), 10);
  }
  for (const std::string d : {"2d", "3d"}) {
    const std::string D = d == "2d" ? "2-D" : "3-D";
    reporter.add_ratio("the drift alone " + D + " (x += h·v, nothing else): per ball at 10^6 / at 10^3",
                       gas(d + "_drift_alone", "1000000"), gas(d + "_drift_alone", "1000"), 1000);
    for (const auto& [steps, balls] : kRegionRuns) {
      const std::string regions =
          "BallGasInRegions/" + d + "/" + std::to_string(steps) + "/" + std::to_string(balls) + "/manual_time";
      const std::string what = "10^6 balls " + D + " as gases of " + std::to_string(balls) + ", " +
                               std::to_string(steps) + " step(s) each in turn";
      reporter.add_ratio(what + " / one gas of 10^3", regions, gas(d, "1000"), 1000);
      reporter.add_ratio(what + " / one gas of 10^6", regions, gas(d, "1000000"));
    }
  }
  for (const char* n : {"1000", "10000", "100000", "1000000"})
    reporter.add_ratio(std::string("ball gas at ") + n + ": 3-D / 2-D per ball (target <= 1.5)", gas("3d", n),
                       gas("2d", n));
  auto settled = [](const std::string& d, const char* n) { return "BallGasSettled/" + d + "/" + n + "/manual_time"; };
  for (const std::string d : {"2d", "3d"})
    reporter.add_ratio("ball gas " + std::string(d == "2d" ? "2-D" : "3-D") + " after 10 s: per ball at 10^6 / at 10^3",
                       settled(d, "1000000"), settled(d, "1000"), 1000);
  for (const char* n : {"1000", "1000000"})
    reporter.add_ratio(std::string("ball gas at ") + n + " after 10 s: 3-D / 2-D per ball", settled("3d", n),
                       settled("2d", n));
  for (const std::string d : {"2d", "3d"})
    for (const auto& [n, power] : {std::pair{"100000", "10^5"}, std::pair{"1000000", "10^6"}})
      reporter.add_ratio("ball gas " + std::string(d == "2d" ? "2-D" : "3-D") + " at " + power +
                             ": numbered at random / lattice's order",
                         gas(d + "_numbered_at_random", n), gas(d, n));
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
