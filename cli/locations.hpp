#pragma once
// Where things are: this executable and its modules, the shipped scenes (and a scene argument's
// file), the shipped assignments, the headers a plug-in is compiled against, the source tree.
#include <string>
#include <vector>

namespace motus::cli {

// This executable, and the folder it is in (from /proc/self/exe).
std::string executable_path();
std::string executable_directory();
// The folder of shipped assignments: $MOTUS_ASSIGNMENTS; else, for an installed motus,
// PREFIX/share/motus/assignments; else the source tree's assignments/.
std::string assignments_directory();
// Where the headers a student's plug-in is compiled against are: `which` is "student",
// "plugin" or "external" (…/motus/WHICH), installed beside this motus or in the source tree.
std::string student_api_directory(const std::string& which);
// The source tree motus was built from ("" when it is gone).
std::string source_directory();
// The folder of shipped scenes: $MOTUS_SCENES; else, for an installed motus, the scenes
// installed beside it (PREFIX/share/motus/scenes); else the source tree's scenes/.
std::string scenes_directory();
// A scene argument as given: a path to a file, or the name of a shipped scene
// ("spring" or "spring.json"). A name that is neither is returned as it is (the loader says "no
// such file"), unless it is a slip away from a shipped scene's: then InputError says which.
std::string resolve_scene_path(const std::string& argument);
// As resolve_scene_path, without the guess.
std::string find_scene_path(const std::string& argument);
// ", did you mean spring?" for a name a slip away from a shipped scene's ("sprng"), else "".
std::string shipped_scene_guess(const std::string& name);
// Every shipped scene file, sorted.
std::vector<std::string> shipped_scenes();

// Where a module of the `motus` command may be (motus-draw.so, motus-peers.so, motus-expressions.so): at $ENV_VAR when
// that is set and not empty (and only there), else next to the executable (the build tree), else
// at `installed`, relative to the executable (where `cmake --install` puts it).
std::vector<std::string> module_candidates(const char* env_var, const std::string& name, const std::string& installed);

}  // namespace motus::cli
