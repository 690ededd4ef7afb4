// ns per step of every Runge-Kutta-family integrator on Lorenz (3 variables).
#include <benchmark/benchmark.h>

#include "motus/integrate/euler.hpp"
#include "motus/integrate/midpoint.hpp"
#include "motus/integrate/rk45.hpp"
#include "motus/integrate/rk4_doubling.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/attractors.hpp"

namespace {

using namespace motus;
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
BENCHMARK(LorenzFixed<Euler>)->Name("Lorenz/euler");
BENCHMARK(LorenzFixed<Midpoint>)->Name("Lorenz/midpoint");

// Adaptive: cost per accepted step at a fixed tolerance (rejections included).
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
BENCHMARK(LorenzAdaptive<Rk4Doubling>)->Name("Lorenz/rk4-doubling");
BENCHMARK(LorenzAdaptive<Rk45>)->Name("Lorenz/rk45");

// The same rk4 through motus::Simulation, as `motus run` drives it: the system is
// behind the FirstOrderSystem interface (one virtual call per derivative).
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
BENCHMARK(LorenzRk4ThroughSimulation)->Name("Lorenz/rk4-through-Simulation-x1000");

}  // namespace
