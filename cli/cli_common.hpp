#pragma once
// What the `motus` subcommands share: finding scenes, the exit codes, and the one-line
// error for input that cannot be used.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "motus/integrator_name.hpp"
#include "motus/scene.hpp"

namespace motus::cli {

// Exit codes: 0 done; 1 the run itself failed; 2 bad input (scene, option or file).
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

// Bad input that is not inside a scene file (an option, an output path): exit 2.
class InputError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// The folder this executable is in (from /proc/self/exe).
std::string executable_directory();
// The folder of shipped scenes: $MOTUS_SCENES; else, for an installed motus, the scenes
// installed beside it (PREFIX/share/motus/scenes); else the source tree's scenes/.
std::string scenes_directory();
// A scene argument as given: a path to a file, or the name of a shipped scene
// ("spring" or "spring.json").
std::string resolve_scene_path(const std::string& argument);
// Every shipped scene file, sorted.
std::vector<std::string> shipped_scenes();

// The integrator a subcommand runs: --integrator when given, else the scene's; one line
// naming the file when it is unknown, or symplectic on a first-order scene.
Integrator integrator_for(const std::string& path, const SceneDescription& scene,
                          const std::optional<std::string>& requested);

// Refuses to overwrite an existing file unless asked to (nothing the user wrote is
// lost without being asked).
void check_can_write(const std::string& path, bool overwrite);

}  // namespace motus::cli
