#pragma once
// --set PATH=VALUE: change one field of a scene's JSON before it is checked.
// PATH is dotted, with [i] for array entries: "bodies[0].mass", "system.parameters.rho".
// VALUE is read as JSON when it is valid JSON (2, [1, 0], true, "text"), else as a string.
#include <nlohmann/json.hpp>
#include <string>

namespace motus {

// Applies one "PATH=VALUE"; throws SceneError(PATH, ...) when the path does not fit, an index
// is too large, or the value is not valid UTF-8.
void apply_override(nlohmann::json& scene, const std::string& assignment);

// Whether `text` is well-formed UTF-8.
bool valid_utf8(const std::string& text);

}  // namespace motus
