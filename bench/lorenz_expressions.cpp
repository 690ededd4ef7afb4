// The cost of a right-hand side written as expressions (the scene file's "equations" system,
// parsed by muparser) against the compiled Lorenz system: one derivative evaluation, and one
// rk4 step, both through the FirstOrderSystem interface (a virtual call per evaluation). That is
// how `motus run` calls an equations system, but not the compiled one: Simulation::advance calls
// the catalog's attractors by their concrete type (with_concrete_system, concrete_system.hpp), with
// direct calls and stages of a size known at compile time — Lorenz/rk4 (lorenz_rk4_vs_hand.cpp).
// bench_integrators prints both ratios: the same interface for both (the cost of the expressions
// alone), and the equations against Lorenz/rk4 (what `motus run` makes a user pay for them).
#include <benchmark/benchmark.h>

#include <memory>

#include "motus/expressions/expression_system.hpp"
#include "motus/integrate/rk4.hpp"
#include "motus/systems/attractors.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;
using motus::bench::minimum;

// Lorenz as a scene file writes it (scenes/lorenz_equations.json), term for term as attractors.hpp.
std::unique_ptr<FirstOrderSystem> lorenz_from_expressions() {
  expressions::Equations e;
  e.variables = {"x", "y", "z"};
  e.parameters = {{"sigma", 10}, {"rho", 28}, {"beta", 8.0 / 3}};
  e.right_hand_sides = {"sigma * (y - x)", "x * (rho - z) - y", "x * y - beta * z"};
  return std::make_unique<expressions::ExpressionSystem>(e);
}

std::unique_ptr<FirstOrderSystem> make(bool expressions) {
  if (expressions) return lorenz_from_expressions();
  return std::make_unique<Lorenz>();
}

void LorenzDerivative(benchmark::State& state, bool expressions) {
  const auto f = make(expressions);
  FirstOrderSystem& system = *f;  // a virtual call per evaluation, for both
  Vector y(3), dydt(3);
  y << 1, 1, 1;
  for (auto _ : state) {
    system.derivative(0, y, dydt);
    y[0] += 1e-12 * dydt[0];  // a new state each time, as in a run
    benchmark::DoNotOptimize(dydt.data());
  }
}
BENCHMARK_CAPTURE(LorenzDerivative, compiled, false)->Name("Lorenz/derivative-compiled-virtual")->ComputeStatistics("min", minimum);
BENCHMARK_CAPTURE(LorenzDerivative, expressions, true)->Name("Lorenz/derivative-expressions")->ComputeStatistics("min", minimum);

// The engine's rk4 on the system through the interface: stages of a size known only at run time,
// a virtual call per evaluation.
void LorenzRk4Step(benchmark::State& state, bool expressions) {
  const auto f = make(expressions);
  FirstOrderSystem& system = *f;
  Vector y = Vector::Ones(3);
  Rk4 stepper;
  stepper.resize(3);
  double t = 0;
  for (auto _ : state) {
    stepper.step(system, t, 1e-3, y);
    t += 1e-3;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK_CAPTURE(LorenzRk4Step, compiled, false)->Name("Lorenz/rk4-step-compiled-virtual")->ComputeStatistics("min", minimum);
BENCHMARK_CAPTURE(LorenzRk4Step, expressions, true)->Name("Lorenz/rk4-step-expressions")->ComputeStatistics("min", minimum);

}  // namespace
