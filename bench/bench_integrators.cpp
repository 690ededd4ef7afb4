// ns per step of every integrator, on Lorenz (a 3-variable first-order system) and on
// the oscillator (one mass on a spring), and a hand-written RK4 loop on Lorenz in the
// same binary: the engine's rk4 must be within 1.10x of it.
//
//   build/bench/bench_integrators [--benchmark_filter=Lorenz]
#include <benchmark/benchmark.h>

#include "motus/integrate/euler.hpp"
#include "motus/integrate/midpoint.hpp"
#include "motus/integrate/rk4.hpp"
#include "motus/integrate/rk45.hpp"
#include "motus/integrate/rk4_doubling.hpp"
#include "motus/integrate/symplectic_euler.hpp"
#include "motus/integrate/symplectic_euler_x.hpp"
#include "motus/integrate/velocity_verlet.hpp"
#include "motus/integrate/verlet.hpp"
#include "motus/integrate/yoshida4.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/attractors.hpp"
#include "motus/systems/mechanical_as_first_order.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;
constexpr double kLorenzStep = 1e-3;
constexpr double kOscillatorStep = 1e-2;

// ---- the hand-written loop: what a student writes from the slide, with plain arrays
void lorenz_by_hand(const double* s, double* d) {
  constexpr double sigma = 10, rho = 28, beta = 8.0 / 3;
  d[0] = sigma * (s[1] - s[0]);
  d[1] = s[0] * (rho - s[2]) - s[1];
  d[2] = s[0] * s[1] - beta * s[2];
}

void LorenzHandWrittenRk4(benchmark::State& state) {
  double y[3] = {1, 1, 1}, k1[3], k2[3], k3[3], k4[3], tmp[3];
  const double h = kLorenzStep;
  for (auto _ : state) {
    lorenz_by_hand(y, k1);
    for (int i = 0; i < 3; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
    lorenz_by_hand(tmp, k2);
    for (int i = 0; i < 3; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
    lorenz_by_hand(tmp, k3);
    for (int i = 0; i < 3; ++i) tmp[i] = y[i] + h * k3[i];
    lorenz_by_hand(tmp, k4);
    for (int i = 0; i < 3; ++i) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    benchmark::DoNotOptimize(y);
  }
}
BENCHMARK(LorenzHandWrittenRk4);

// ---- the engine's integrators, called on the concrete system
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
BENCHMARK(LorenzFixed<Rk4>)->Name("Lorenz/rk4");

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
  scene.first_order = FirstOrderDescription{"lorenz", {{"sigma", 10}, {"rho", 28}, {"beta", 8.0 / 3}}, {1, 1, 1}};
  Simulation sim(scene, Integrator::Rk4);
  constexpr long kSteps = 1000;
  for (auto _ : state) sim.advance(sim.time() + kSteps * kLorenzStep, kLorenzStep, {});
  state.SetItemsProcessed(state.iterations() * kSteps);
  state.counters["ns_per_step"] =
      benchmark::Counter(static_cast<double>(state.iterations() * kSteps), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(LorenzRk4ThroughSimulation)->Name("Lorenz/rk4-through-Simulation-x1000");

// ---- the oscillator: one 1-D mass on a zero-length spring (m = 1, k = 1)
MechanicalSystem oscillator() {
  ForceSet forces;
  Spring s;
  s.stiffness = 1;
  forces.springs.push_back(s);
  return MechanicalSystem(1, {1.0}, forces);
}

template <class Stepper>
void OscillatorRungeKutta(benchmark::State& state) {
  MechanicalSystem m = oscillator();
  MechanicalAsFirstOrder f(m);
  Vector y(2);
  y << 1, 0;
  Stepper stepper;
  stepper.resize(2);
  double t = 0;
  for (auto _ : state) {
    stepper.step(f, t, kOscillatorStep, y);
    t += kOscillatorStep;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(OscillatorRungeKutta<Euler>)->Name("Oscillator/euler");
BENCHMARK(OscillatorRungeKutta<Midpoint>)->Name("Oscillator/midpoint");
BENCHMARK(OscillatorRungeKutta<Rk4>)->Name("Oscillator/rk4");

template <class Stepper>
void OscillatorAdaptive(benchmark::State& state) {
  MechanicalSystem m = oscillator();
  MechanicalAsFirstOrder f(m);
  Vector y(2);
  y << 1, 0;
  Stepper stepper;
  stepper.resize(2);
  stepper.set_tolerance({1e-9, 1e-9});
  double t = 0, h = kOscillatorStep;
  for (auto _ : state) {
    stepper.try_step(f, t, h, y);
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(OscillatorAdaptive<Rk4Doubling>)->Name("Oscillator/rk4-doubling");
BENCHMARK(OscillatorAdaptive<Rk45>)->Name("Oscillator/rk45");

template <class Stepper>
void OscillatorSymplectic(benchmark::State& state) {
  MechanicalSystem m = oscillator();
  Vector x = Vector::Ones(1), v = Vector::Zero(1);
  Stepper stepper;
  stepper.resize(1);
  double t = 0;
  for (auto _ : state) {
    stepper.step(m, t, kOscillatorStep, x, v);
    t += kOscillatorStep;
    benchmark::DoNotOptimize(x.data());
  }
}
BENCHMARK(OscillatorSymplectic<SymplecticEuler>)->Name("Oscillator/symplectic-euler");
BENCHMARK(OscillatorSymplectic<SymplecticEulerX>)->Name("Oscillator/symplectic-euler-x");
BENCHMARK(OscillatorSymplectic<Verlet>)->Name("Oscillator/verlet");
BENCHMARK(OscillatorSymplectic<VelocityVerlet>)->Name("Oscillator/velocity-verlet");
BENCHMARK(OscillatorSymplectic<Yoshida4>)->Name("Oscillator/yoshida4");

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  motus::bench::RatioReporter reporter;
  reporter.add_ratio("engine rk4 / hand-written rk4 on Lorenz (target <= 1.10)", "Lorenz/rk4", "LorenzHandWrittenRk4");
  reporter.add_ratio("rk4 through Simulation (per 1000 steps) / hand loop", "Lorenz/rk4-through-Simulation-x1000",
                     "LorenzHandWrittenRk4");
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
