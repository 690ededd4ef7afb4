// A shipped scene file, read by the installed scene library and run by the installed
// comparison in motus, Box2D and Bullet: two balls of masses 1 and 3 meeting head on with
// e = 1. Prints each engine's final velocities; the exact answer is in the course's
// formula for an elastic collision, v_a' = ((m_a − m_b) v_a + 2 m_b v_b) / (m_a + m_b).
//   head_on_in_three_engines SCENES_DIR
#include <cstdio>
#include <string>

#include "motus/compare/backends/backend.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/simulation.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENES_DIR\n", argv[0]);
    return 2;
  }
  const motus::SceneDescription scene = motus::load_scene(std::string(argv[1]) + "/head_on.json");
  const long steps = motus::fixed_step_count(scene.duration, scene.dt);
  for (const char* engine : {"motus", "box2d", "bullet"}) {
    auto backend = motus::compare::make_backend(engine);
    backend->build(scene, motus::Integrator::SymplecticEuler, scene.dt);
    for (long i = 0; i < steps; ++i) backend->step();
    motus::compare::Snapshot s;
    backend->read(s);
    const int d = scene.mechanical->dimensions;
    std::printf("%-7s", engine);
    for (size_t i = 0; i < scene.mechanical->bodies.size(); ++i) std::printf(" %10.6f", s.v[i * d]);
    std::printf("\n");
  }
  return 0;
}
