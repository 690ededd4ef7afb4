#pragma once
// Reading a scene's "system": {"type": "equations", ...}: a first-order system whose right-hand
// sides are expressions (docs/scene-format.md, "equations"). Every name, every equation and the
// initial state are checked here, and the expressions are parsed once to find the first problem
// (with its column); the description then carries a factory that parses them again for each run
// (motus::expressions), so the engine builds the system without knowing how.
#include "motus/scene.hpp"
#include "motus/scene_file/json_fields.hpp"

namespace motus {

// The most variables an "equations" system may have.
constexpr int kMaxEquations = 1000;

// `system` is the scene's "system" object, whose "type" is "equations" (already read).
FirstOrderDescription read_equations_system(JsonFields& system);

}  // namespace motus
