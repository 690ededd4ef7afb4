// Frames per second of the renderer at 640 × 480 (2× supersampled, so 1280 × 960 rasterised), on one
// core: llvmpipe is told to use no rasteriser threads (LP_NUM_THREADS=0, set before the first context).
//   BM_DrawFrame  draw_frame + Canvas::image (what a frame costs before it is written)
//   BM_DrawAndPng the same plus write_png (zlib level 1, its default) to a file: what `motus render` pays per frame
// on the ball gas with 1,000 balls (scenes/ball_gas.json with lattice.count=1000, as --set does) and on
// the cloth (scenes/cloth.json, 400 particles, 1,482 sticks drawn as shaded triangles). The states are a
// recorded run of 30 frames, cycled; the simulation itself is not timed. Target: 30 fps or more.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "motus/render/canvas.hpp"
#include "motus/render/draw.hpp"
#include "motus/simulation.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace {

struct Prepared {
  motus::SceneDescription scene;
  motus::render::Recording recording;
};

const Prepared& prepared(const std::string& name) {
  static std::map<std::string, Prepared> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  Prepared p;
  p.scene = motus::load_scene(std::string(MOTUS_SCENES_DIR) + "/" + name + ".json",
                              name == "ball_gas" ? std::vector<std::string>{"lattice.count=1000"} : std::vector<std::string>{});
  motus::Simulation sim(p.scene, *motus::integrator_from_name(p.scene.integrator));
  for (int k = 0; k < 30; ++k) {
    if (k) sim.advance(sim.time() + 1.0 / 30, p.scene.dt, {p.scene.atol, p.scene.rtol});
    p.recording.add(sim.time(), {sim.state().data(), static_cast<size_t>(sim.state().size())}, sim.energy()->total);
  }
  return cache.emplace(name, std::move(p)).first->second;
}

void run(benchmark::State& state, const std::string& name, bool png) {
  const Prepared& p = prepared(name);
  motus::render::Canvas canvas(640, 480, 2);
  const auto view = canvas.full();
  const auto camera = motus::render::fit_camera(p.scene, p.recording, view);
  motus::render::DrawOptions options;
  motus::render::fit_ground(p.scene, p.recording, options);
  motus::render::Image image;
  const std::string file = (std::filesystem::temp_directory_path() / ("motus_bench_render_" + name + ".png")).string();
  size_t k = 0;
  for (auto _ : state) {
    motus::render::draw_frame(canvas, view, p.scene, p.recording, k++ % p.recording.size(), camera, options);
    canvas.image(image);
    if (png) motus::render::write_png(file, image);
    benchmark::DoNotOptimize(image.rgba.data());
  }
  state.counters["fps"] = benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  std::filesystem::remove(file);
}

void BM_DrawFrame(benchmark::State& state, const char* name) { run(state, name, false); }
void BM_DrawAndPng(benchmark::State& state, const char* name) { run(state, name, true); }

BENCHMARK_CAPTURE(BM_DrawFrame, ball_gas_1000, "ball_gas")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_DrawFrame, cloth, "cloth")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_DrawAndPng, ball_gas_1000, "ball_gas")->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_DrawAndPng, cloth, "cloth")->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  setenv("LP_NUM_THREADS", "0", 0);  // one core: llvmpipe rasterises on the calling thread
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
