#pragma once
// JSON text read as strictly as a scene file is: a NUL byte, a key twice in one object and
// nesting past kMaxNesting are refused, and a malformed document is named by line, column and
// field path. The grader reads an assignment's own files (assignment.json, rubric.json, the
// tests) the same way, so that what an instructor wrote is never read as something else.
#include <nlohmann/json.hpp>
#include <string>

namespace motus {

// Throws SceneFileError(file, field, message) (motus/scene_file/scene_file.hpp).
nlohmann::json parse_strict_json(const std::string& text, const std::string& file);

}  // namespace motus
