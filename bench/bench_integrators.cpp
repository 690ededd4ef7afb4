// bench_integrators: ns per step of every integrator that can run each system — on Lorenz (a
// 3-variable first-order system: the Runge–Kutta family, euler to dop853) and on the oscillator
// (one mass on a spring: all eleven) — a hand-written RK4 loop on Lorenz in the same binary,
// the engine's rk4 with its stage updates as plain loops against the same as Eigen expressions,
// and Lorenz written as expressions (the scene file's "equations", muparser) beside the compiled
// one; prints the ratios of one run at the end (the fastest repetitions', the medians' beside).
//
//   build/bench/bench_integrators [--benchmark_filter=Lorenz] [--benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true]
#include <benchmark/benchmark.h>

#include "ratio_reporter.hpp"

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  motus::bench::RatioReporter reporter;
  reporter.add_ratio("engine rk4 / hand-written rk4 on Lorenz (target <= 1.10)", "Lorenz/rk4", "LorenzHandWrittenRk4");
  reporter.add_ratio("rk4 through Simulation::advance (concrete Lorenz) / hand loop", "Lorenz/rk4-through-Simulation-x1000",
                     "LorenzHandWrittenRk4", 1000);
  reporter.add_ratio("rk4 stages as Eigen expressions / plain loops, fixed size", "Lorenz/rk4-stages-fixed-size/eigen",
                     "Lorenz/rk4-stages-fixed-size/loops");
  reporter.add_ratio("rk4 stages as Eigen expressions / plain loops, dynamic size", "Lorenz/rk4-stages-dynamic-size/eigen",
                     "Lorenz/rk4-stages-dynamic-size/loops");
  reporter.add_ratio("Lorenz as expressions / compiled, one derivative, both virtual", "Lorenz/derivative-expressions",
                     "Lorenz/derivative-compiled-virtual");
  reporter.add_ratio("Lorenz as expressions / compiled, one rk4 step, both virtual", "Lorenz/rk4-step-expressions",
                     "Lorenz/rk4-step-compiled-virtual");
  reporter.add_ratio("rk4 step as motus run calls each: expressions / concrete", "Lorenz/rk4-step-expressions",
                     "Lorenz/rk4");
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
