// bench_constraints: the shipped scenes held together by sticks — cloth, rope, ragdoll,
// stick_pendulum (scenes/*.json, as `motus compare` loads them) — in motus and its two peers,
// Box2D 2.4 and Bullet 3 (compare/'s backends, with docs/peers.md's fair settings): CPU time per
// step, and the largest stick error of one whole run of the scene (measured outside the timing
// by compare's metrics, the same code for every engine). Issue 13: motus is to be the fastest
// with the smallest stick error on each.
//
// Each iteration is one step of the scene; at the scene's end the world is built again (outside
// the timing), so the steps timed are the scene's own, start to end, over and over. Five
// repetitions, interleaved at random; the ratios at the end are between the fastest repetitions,
// with the medians' ratio beside them (ratio_reporter.hpp).
//
//   build/bench/bench_constraints [--benchmark_filter=cloth]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <string>

#include "motus/compare/backends/backend.hpp"
#include "motus/compare/metrics.hpp"
#include "motus/integrate/method.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/simulation.hpp"
#include "ratio_reporter.hpp"

namespace {

using namespace motus;

const SceneDescription& scene_named(const std::string& name) {
  static std::map<std::string, SceneDescription> scenes;
  auto it = scenes.find(name);
  if (it == scenes.end()) it = scenes.emplace(name, load_scene(std::string(MOTUS_SCENES_DIR) + "/" + name + ".json")).first;
  return it->second;
}

// The largest relative stick-length error over one whole run, every step.
double largest_stick_error(const SceneDescription& scene, const std::string& engine) {
  const compare::Metrics metrics(scene);
  auto backend = compare::make_backend(engine);
  backend->build(scene, Method(Integrator::Verlet), scene.dt);
  compare::Snapshot s;
  backend->read(s);
  double worst = metrics.measure(s, nullptr).constraint_error;
  const long steps = fixed_step_count(scene.duration, scene.dt);
  for (long i = 0; i < steps; ++i) {
    backend->step();
    backend->read(s);
    worst = std::max(worst, metrics.measure(s, nullptr).constraint_error);
  }
  return worst;
}

void Constraints(benchmark::State& state, const std::string& scene_name, const std::string& engine) {
  const SceneDescription& scene = scene_named(scene_name);
  const long steps = fixed_step_count(scene.duration, scene.dt);
  auto build = [&] {
    auto backend = compare::make_backend(engine);
    backend->build(scene, Method(Integrator::Verlet), scene.dt);
    backend->watch_for_notes(false);  // (timed: the engine's step alone, as motus compare times it)
    return backend;
  };
  std::unique_ptr<compare::Backend> backend;
  try {
    backend = build();
  } catch (const compare::Unsupported&) {
    state.SkipWithError((engine + " cannot run " + scene_name).c_str());
    return;
  }
  long step = 0;
  for (auto _ : state) {
    if (step == steps) {  // the scene's end: from its start again, untimed
      state.PauseTiming();
      backend = build();
      step = 0;
      state.ResumeTiming();
    }
    backend->step();
    ++step;
  }
  state.counters["largest_stick_error"] = largest_stick_error(scene, engine);
}

const char* const kScenes[] = {"cloth", "rope", "ragdoll", "stick_pendulum"};
const char* const kEngines[] = {"motus", "box2d", "bullet"};

}  // namespace

int main(int argc, char** argv) {
  for (const char* scene : kScenes)
    for (const char* engine : kEngines) {
      if (std::string(scene) == "cloth" && std::string(engine) == "box2d") continue;  // 3-D: Box2D is 2-D only
      motus::bench::with_min(benchmark::RegisterBenchmark((std::string("Constraints/") + scene + "/" + engine).c_str(),
                                                          Constraints, std::string(scene), std::string(engine)))
          ->Unit(benchmark::kMicrosecond);
    }
  motus::bench::initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  motus::bench::RatioReporter reporter;
  for (const char* scene : kScenes)
    for (const char* engine : {"box2d", "bullet"}) {
      if (std::string(scene) == "cloth" && std::string(engine) == "box2d") continue;
      reporter.add_ratio(std::string(scene) + ": " + engine + " / motus, time per step (target > 1)",
                         std::string("Constraints/") + scene + "/" + engine, std::string("Constraints/") + scene + "/motus");
    }
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}
