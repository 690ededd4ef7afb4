// The engine's rk4 writes its stage updates as plain loops over the state (rk4.hpp); the same
// step with them written as Eigen expressions (y_stage = y + 0.5 * h * k1, …), on the concrete
// Lorenz, in both kinds of storage the engine uses: stages of a size known at compile time (a
// fresh set on the stack each step, as for the attractors and one body) and of a size known at
// run time (Vectors sized once, as for any other system). The loops are the engine's own Rk4;
// the expressions do the same arithmetic in the same order and give the same numbers. Alone in
// its translation unit, like lorenz_rk4_vs_hand.cpp, so that the four are inlined alike.
#include <benchmark/benchmark.h>

#include "motus/integrate/rk4.hpp"
#include "motus/systems/attractors.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;
using motus::bench::minimum;
constexpr double kLorenzStep = 1e-3;

template <int N>
struct Stages {
  Eigen::Matrix<double, N, 1> k1, k2, k3, k4, y_stage;
};

// Lorenz without its size known at compile time (no static_size), still called directly (its
// derivative is final): the engine's Rk4 then keeps its stages in Vectors sized once.
struct LorenzOfRunTimeSize {
  Lorenz lorenz;
  int size() const { return lorenz.size(); }
  void derivative(double t, ConstVectorRef y, VectorRef dydt) { lorenz.derivative(t, y, dydt); }
};

// The same with each loop an Eigen expression.
template <int N>
void step_eigen(Lorenz& f, double t, double h, VectorRef y, Stages<N>& s) {
  auto& [k1, k2, k3, k4, y_stage] = s;
  f.derivative(t, y, k1);
  y_stage = y + 0.5 * h * k1;
  f.derivative(t + 0.5 * h, y_stage, k2);
  y_stage = y + 0.5 * h * k2;
  f.derivative(t + 0.5 * h, y_stage, k3);
  y_stage = y + h * k3;
  f.derivative(t + h, y_stage, k4);
  y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
}

template <bool kEigen>
void LorenzRk4FixedSize(benchmark::State& state) {
  Lorenz f;
  Rk4 engine;
  Vector y = Vector::Ones(3);
  double t = 0;
  for (auto _ : state) {
    if constexpr (kEigen) {
      Stages<3> s;  // as Rk4::step makes them for a system of static_size 3
      step_eigen(f, t, kLorenzStep, y, s);
    } else {
      engine.step(f, t, kLorenzStep, y);
    }
    t += kLorenzStep;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(LorenzRk4FixedSize<false>)->Name("Lorenz/rk4-stages-fixed-size/loops")->ComputeStatistics("min", minimum);
BENCHMARK(LorenzRk4FixedSize<true>)->Name("Lorenz/rk4-stages-fixed-size/eigen")->ComputeStatistics("min", minimum);

template <bool kEigen>
void LorenzRk4DynamicSize(benchmark::State& state) {
  LorenzOfRunTimeSize f;
  Rk4 engine;
  engine.resize(3);
  Stages<Eigen::Dynamic> s;  // as Rk4::resize sizes them once
  for (auto* v : {&s.k1, &s.k2, &s.k3, &s.k4, &s.y_stage}) v->resize(3);
  Vector y = Vector::Ones(3);
  double t = 0;
  for (auto _ : state) {
    if constexpr (kEigen) step_eigen(f.lorenz, t, kLorenzStep, y, s);
    else engine.step(f, t, kLorenzStep, y);
    t += kLorenzStep;
    benchmark::DoNotOptimize(y.data());
  }
}
BENCHMARK(LorenzRk4DynamicSize<false>)->Name("Lorenz/rk4-stages-dynamic-size/loops")->ComputeStatistics("min", minimum);
BENCHMARK(LorenzRk4DynamicSize<true>)->Name("Lorenz/rk4-stages-dynamic-size/eigen")->ComputeStatistics("min", minimum);

}  // namespace
