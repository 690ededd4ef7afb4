// bench_plugin: what it costs to run a student's integrator through a plug-in. The same code —
// the integrators assignment's reference solution — once built into this program and once
// loaded as a plug-in (dlopen, --plugin), each stepping one Kepler orbit at h = 0.01 (629
// steps) through motus::Simulation; and motus's own beside them, for scale (the student's code
// allocates its stages, motus's does not): RK4, and velocity Verlet three ways. Ratios in one run
// (RatioReporter).
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "motus/exact/exact_solution.hpp"
#include "motus/plugin/plugin_set.hpp"
#include "motus/simulation.hpp"
#include "ratio_reporter.hpp"

// The solution's plug-in entry point, built into this program (from its own plugin.cpp).
extern "C" const motus::PluginEntry* motus_plugin();

namespace {

using namespace motus;
using motus::bench::minimum;

SceneDescription kepler() {
  SceneDescription scene;
  MechanicalDescription m;
  m.dimensions = 2;
  BodyDescription body;
  body.position = {0.4, 0};
  body.velocity = {0, 2};
  m.bodies.push_back(body);
  CentralGravity g;
  g.mu = 1;
  m.forces.central_gravity.push_back(g);
  scene.mechanical = m;
  scene.exact = "kepler";
  return scene;
}

constexpr double kH = 0.01, kOrbit = 2 * std::numbers::pi;

const ExternalIntegrator& find(const PluginEntry* entry, const char* name) {
  for (int i = 0; i < entry->integrator_count; ++i)
    if (std::string(entry->integrators[i].name) == name) return entry->integrators[i];
  throw std::runtime_error(std::string("no integrator ") + name);
}

void run_orbits(benchmark::State& state, const Method& method) {
  const SceneDescription scene = kepler();
  double error = 0;
  for (auto _ : state) {
    Simulation sim(scene, method);
    sim.advance(kOrbit, kH, {});
    error = (sim.state() - *exact_state(scene, sim.time())).cwiseAbs().maxCoeff();
    benchmark::DoNotOptimize(sim.state().data());
  }
  state.counters["error_at_2pi"] = error;  // the same method: the same error
}

void MotusRk4(benchmark::State& state) { run_orbits(state, Integrator::Rk4); }
BENCHMARK(MotusRk4)->ComputeStatistics("min", minimum);

void StudentRk4BuiltIn(benchmark::State& state) {
  run_orbits(state, Method(find(motus_plugin(), "rk4"), "student:rk4"));
}
BENCHMARK(StudentRk4BuiltIn)->ComputeStatistics("min", minimum);

void StudentRk4Plugin(benchmark::State& state) {
  static PluginSet plugins;
  if (plugins.empty()) plugins.load(MOTUS_SOLUTION_PLUGIN);
  run_orbits(state, *plugins.integrator("student:rk4"));
}
BENCHMARK(StudentRk4Plugin)->ComputeStatistics("min", minimum);

void MotusVelocityVerlet(benchmark::State& state) { run_orbits(state, Integrator::VelocityVerlet); }
BENCHMARK(MotusVelocityVerlet)->ComputeStatistics("min", minimum);

void StudentVelocityVerletBuiltIn(benchmark::State& state) {
  run_orbits(state, Method(find(motus_plugin(), "velocity-verlet"), "student:velocity-verlet"));
}
BENCHMARK(StudentVelocityVerletBuiltIn)->ComputeStatistics("min", minimum);

void StudentVelocityVerletPlugin(benchmark::State& state) {
  static PluginSet plugins;
  if (plugins.empty()) plugins.load(MOTUS_SOLUTION_PLUGIN);
  run_orbits(state, *plugins.integrator("student:velocity-verlet"));
}
BENCHMARK(StudentVelocityVerletPlugin)->ComputeStatistics("min", minimum);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  motus::bench::RatioReporter reporter;
  reporter.add_ratio("rk4: the solution as a plug-in / the same code built in", "StudentRk4Plugin", "StudentRk4BuiltIn");
  reporter.add_ratio("rk4: the solution built in / motus's own rk4", "StudentRk4BuiltIn", "MotusRk4");
  reporter.add_ratio("velocity Verlet: as a plug-in / built in", "StudentVelocityVerletPlugin",
                     "StudentVelocityVerletBuiltIn");
  reporter.add_ratio("velocity Verlet: built in / motus's own", "StudentVelocityVerletBuiltIn", "MotusVelocityVerlet");
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
