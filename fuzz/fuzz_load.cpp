// fuzz_load: the scene loader with --set overrides. Every input must end in a scene or in a
// SceneFileError (one line: file, field, message); anything else — a crash, a hang, another
// exception, memory misuse or undefined behaviour — is a finding.
#include <cstdlib>

#include "fuzz_input.hpp"
#include "motus/scene_file/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto input = motus::fuzz::split(data, size);
  try {
    const motus::SceneDescription scene = motus::parse_scene(input.scene, "fuzz.json", input.overrides);
    (void)scene;
  } catch (const motus::SceneFileError& e) {
    if (std::string(e.what()).size() > 600) std::abort();  // an error line stays a few hundred characters
  }
  return 0;
}
