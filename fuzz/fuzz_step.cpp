// fuzz_step: load a scene, build it and take a few steps (at most 20, and at most 2,000
// accepted or rejected adaptive attempts) with its own integrator, for scenes of at most 200
// bodies (a 400-ball gas at dt = 5 s, each ball crossing its whole box in one step, takes 11 s
// for 20 steps under the sanitizers — 0.2 s in Release —, which is slow, not stuck). Allowed endings: a
// SceneFileError or SceneError (bad input) and std::runtime_error (a run that fails: a state that
// overflows, a step size that underflows); a crash, a hang, another exception, memory misuse or
// undefined behaviour is a finding. (The grid that never returned for infinite positions would
// have been found here.)
#include <cstdlib>

#include "fuzz_input.hpp"
#include "motus/scene_error.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/simulation.hpp"

namespace {

struct TooMuchWork {};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto input = motus::fuzz::split(data, size);
  try {
    const motus::SceneDescription scene = motus::parse_scene(input.scene, "fuzz.json", input.overrides);
    if (scene.mechanical && scene.mechanical->bodies.size() > 200) return 0;  // keep each input quick
    const auto integrator = motus::integrator_from_name(scene.integrator);
    motus::Simulation sim(scene, *integrator);
    long attempts = 0;
    sim.advance(sim.time() + 20 * scene.dt, scene.dt, {scene.atol, scene.rtol}, [&](const motus::Simulation& s) {
      if (++attempts > 2000 || s.rejected() > 2000) throw TooMuchWork{};
    });
  } catch (const motus::SceneFileError&) {
  } catch (const motus::SceneError&) {
  } catch (const std::runtime_error&) {
  } catch (const TooMuchWork&) {
  }
  return 0;
}
