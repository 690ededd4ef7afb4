// bench_integrators: ns per step of every integrator, on Lorenz (a 3-variable
// first-order system) and on the oscillator (one mass on a spring), and a hand-written
// RK4 loop on Lorenz in the same binary, and Lorenz written as expressions (the scene file's
// "equations", muparser) beside the compiled one; prints the ratios of one run at the end.
//
//   build/bench/bench_integrators [--benchmark_filter=Lorenz]
#include <benchmark/benchmark.h>

#include "ratio_reporter.hpp"

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  motus::bench::RatioReporter reporter;
  reporter.add_ratio("engine rk4 / hand-written rk4 on Lorenz (target <= 1.10)", "Lorenz/rk4", "LorenzHandWrittenRk4");
  reporter.add_ratio("rk4 through Simulation (virtual derivative) / hand loop", "Lorenz/rk4-through-Simulation-x1000",
                     "LorenzHandWrittenRk4", 1000);
  reporter.add_ratio("Lorenz as expressions (muparser) / compiled, one derivative", "Lorenz/derivative-expressions",
                     "Lorenz/derivative-compiled");
  reporter.add_ratio("Lorenz as expressions (muparser) / compiled, one rk4 step", "Lorenz/rk4-step-expressions",
                     "Lorenz/rk4-step-compiled");
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
