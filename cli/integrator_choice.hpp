#pragma once
// The integrator a run uses (--integrator, a plug-in's or the scene's), and the messages that name
// integrators and plug-ins: an unknown name, a plug-in the run does not use, a state no longer finite.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "motus/integrate/method.hpp"
#include "motus/plugin/plugin_set.hpp"
#include "motus/scene.hpp"

namespace motus {
class Simulation;
class World;
}

namespace motus::cli {

// The integrator a subcommand runs: --integrator when given (a built-in, or PLUGIN:NAME from
// a loaded plug-in), else the scene's; one line naming the file when it is unknown, or
// symplectic on a first-order scene.
Method method_for(const std::string& path, const SceneDescription& scene, const std::optional<std::string>& requested);
// {"euler", "midpoint", ..., "student:euler", ...}: the built-in integrators and the plug-ins', for messages.
std::vector<std::string> known_integrators();
// Names joined by ", " in at most `budget` bytes, each whole: those that do not fit are counted at
// the end ("euler, midpoint, …and 12 more"). (main prints a message as one line of at most 400
// bytes, cut in its middle: a long list of integrators was cut inside a name, "symplectic-eule…verlet".)
std::string whole_names(const std::vector<std::string>& names, size_t budget);
// The room a list has in a message that is `before` it and `after` it: what keeps the whole within
// main's one line of 400 bytes, and at least 120 bytes (a path or a name that takes the rest is
// what main then cuts, in the middle, and the list at the end is kept).
size_t room_for_list(const std::string& before, const std::string& after);
// What a loaded plug-in brings, in words: "8 integrators (student:euler, student:midpoint, …)",
// "collision rules", "a constraint projection", joined by "and"; "nothing" when it brings none.
std::string what_plugin_brings(const LoadedPlugin& plugin);
// One line for standard error ("note: the plug-in cloth.so brings a constraint projection, and spring
// has no sticks or pins: it is not used in this run"), for each loaded plug-in of which a run uses
// nothing: not its integrator (`method` is not one of its), nor its collision rules or its
// projection (the scene's `world` runs no such pass; null for a first-order system). Nothing when
// no plug-in is loaded or every one is used. `scene_name` names the scene in the note.
std::vector<std::string> unused_plugin_notes(const std::string& scene_name, const Method& method, const World* world);

// What to suspect when a run's state stops being finite: what the scene's system says made it so
// (an equation that gave a NaN: FirstOrderSystem::why_not_finite); else a plug-in's integrator
// (`method`) or its collision response or constraint projection when one ran, named with its file;
// otherwise the step, too large for the integrator. One clause, for "the state was no longer
// finite by t = …". (`smaller_step`: how this command takes a smaller step; render has no --dt.)
std::string non_finite_suspect(const Simulation& sim, const Method& method, const std::string& smaller_step = "a smaller --dt");

}  // namespace motus::cli
