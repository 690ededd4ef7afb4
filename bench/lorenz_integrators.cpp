// ns per step of every Runge-Kutta-family integrator on Lorenz (3 variables): euler, midpoint,
// rk4-doubling, rk45 and dop853 here, rk4 in lorenz_rk4_vs_hand.cpp; and rk4 through
// Simulation::advance. (The symplectic family needs positions and velocities apart: it cannot
// run Lorenz.)
#include <benchmark/benchmark.h>

#include "motus/integrate/dop853.hpp"
#include "motus/integrate/euler.hpp"
#include "motus/integrate/midpoint.hpp"
#include "motus/integrate/rk45.hpp"
#include "motus/integrate/rk4_doubling.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/attractors.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;
using motus::bench::minimum;
constexpr double kLorenzStep = 1e-3;

// The engine's integrators, called on the concrete system.
template <class Stepper>
void LorenzFixed(benchmark::State& state) {
  Lorenz f;
  Vector y = Vector::Ones(3);
  Stepper stepper;
  stepper.resize(3);
  double t = 0;
  for (auto _ : state) {
    stepper.step(f, t, kLorenzStep, y);
    t += kLorenzStep;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(LorenzFixed<Euler>)->Name("Lorenz/euler")->ComputeStatistics("min", minimum);
BENCHMARK(LorenzFixed<Midpoint>)->Name("Lorenz/midpoint")->ComputeStatistics("min", minimum);

// Adaptive: cost per attempted step (one try_step, accepted or rejected) at a fixed tolerance,
// from a step size the controller chooses as it goes; accepted_fraction is the share of the
// attempts that were accepted (divide the time by it for the cost per accepted step).
template <class Stepper>
void LorenzAdaptive(benchmark::State& state) {
  Lorenz f;
  Vector y = Vector::Ones(3);
  Stepper stepper;
  stepper.resize(3);
  stepper.set_tolerance({1e-9, 1e-9});
  double t = 0, h = kLorenzStep;
  long accepted = 0;
  for (auto _ : state) {
    accepted += stepper.try_step(f, t, h, y);
    benchmark::DoNotOptimize(y.data());
  }
  state.counters["accepted_fraction"] = static_cast<double>(accepted) / static_cast<double>(state.iterations());
}
BENCHMARK(LorenzAdaptive<Rk4Doubling>)->Name("Lorenz/rk4-doubling")->ComputeStatistics("min", minimum);
BENCHMARK(LorenzAdaptive<Rk45>)->Name("Lorenz/rk45")->ComputeStatistics("min", minimum);
BENCHMARK(LorenzAdaptive<Dop853>)->Name("Lorenz/dop853")->ComputeStatistics("min", minimum);

// The same rk4 through motus::Simulation::advance, as `motus run` drives it: advance calls the
// scene's Lorenz by its concrete type (with_concrete_system, concrete_system.hpp), so this is the
// cost of advance's loop around the steps, not of a virtual call (there is none).
void LorenzRk4ThroughSimulation(benchmark::State& state) {
  SceneDescription scene;
  FirstOrderDescription lorenz;
  lorenz.type = "lorenz";
  lorenz.parameters = {{"sigma", 10}, {"rho", 28}, {"beta", 8.0 / 3}};
  lorenz.initial = {1, 1, 1};
  scene.first_order = lorenz;
  Simulation sim(scene, Integrator::Rk4);
  constexpr long kSteps = 1000;
  for (auto _ : state) sim.advance(sim.time() + kSteps * kLorenzStep, kLorenzStep, {});
  state.SetItemsProcessed(state.iterations() * kSteps);
  state.counters["ns_per_step"] =
      benchmark::Counter(static_cast<double>(state.iterations() * kSteps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(LorenzRk4ThroughSimulation)->Name("Lorenz/rk4-through-Simulation-x1000")->ComputeStatistics("min", minimum);

}  // namespace
