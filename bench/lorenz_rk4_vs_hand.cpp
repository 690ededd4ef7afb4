// The engine's rk4 against a hand-written RK4 loop on Lorenz: the engine's must be
// within 1.10x. Alone in its translation unit, so that GCC's whole-file inlining budget
// (spent differently as other benchmarks are added) treats both loops alike.
#include <benchmark/benchmark.h>

#include "motus/integrate/rk4.hpp"
#include "motus/systems/attractors.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;
using motus::bench::minimum;
constexpr double kLorenzStep = 1e-3;

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
BENCHMARK(LorenzHandWrittenRk4)->ComputeStatistics("min", minimum);

// ---- the engine's rk4, called on the concrete system (as Simulation::advance, and so `motus run`, calls it)
void LorenzEngineRk4(benchmark::State& state) {
  Lorenz f;
  Vector y = Vector::Ones(3);
  Rk4 stepper;
  stepper.resize(3);
  double t = 0;
  for (auto _ : state) {
    stepper.step(f, t, kLorenzStep, y);
    t += kLorenzStep;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(LorenzEngineRk4)->Name("Lorenz/rk4")->ComputeStatistics("min", minimum);

}  // namespace
