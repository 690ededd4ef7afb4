// ns per step of every integrator on the oscillator: one 1-D mass on a spring (the adaptive ones:
// per attempted step, from a step size their controller chooses as it goes).
#include <benchmark/benchmark.h>

#include "motus/integrate/dop853.hpp"
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
#include "motus/systems/mechanical_as_first_order.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;
using motus::bench::minimum;
constexpr double kOscillatorStep = 1e-2;

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
BENCHMARK(OscillatorRungeKutta<Euler>)->Name("Oscillator/euler")->ComputeStatistics("min", minimum);
BENCHMARK(OscillatorRungeKutta<Midpoint>)->Name("Oscillator/midpoint")->ComputeStatistics("min", minimum);
BENCHMARK(OscillatorRungeKutta<Rk4>)->Name("Oscillator/rk4")->ComputeStatistics("min", minimum);

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
BENCHMARK(OscillatorAdaptive<Rk4Doubling>)->Name("Oscillator/rk4-doubling")->ComputeStatistics("min", minimum);
BENCHMARK(OscillatorAdaptive<Rk45>)->Name("Oscillator/rk45")->ComputeStatistics("min", minimum);
BENCHMARK(OscillatorAdaptive<Dop853>)->Name("Oscillator/dop853")->ComputeStatistics("min", minimum);

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
BENCHMARK(OscillatorSymplectic<SymplecticEuler>)->Name("Oscillator/symplectic-euler")->ComputeStatistics("min", minimum);
BENCHMARK(OscillatorSymplectic<SymplecticEulerX>)->Name("Oscillator/symplectic-euler-x")->ComputeStatistics("min", minimum);
BENCHMARK(OscillatorSymplectic<Verlet>)->Name("Oscillator/verlet")->ComputeStatistics("min", minimum);
BENCHMARK(OscillatorSymplectic<VelocityVerlet>)->Name("Oscillator/velocity-verlet")->ComputeStatistics("min", minimum);
BENCHMARK(OscillatorSymplectic<Yoshida4>)->Name("Oscillator/yoshida4")->ComputeStatistics("min", minimum);

}  // namespace
