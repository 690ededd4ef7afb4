#include "motus/scene_file/scene_overrides.hpp"

#include <algorithm>
#include <cctype>

#include "motus/scene_error.hpp"

namespace motus {

void apply_override(nlohmann::json& scene, const std::string& assignment) {
  const auto equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0)
    throw SceneError(assignment, "--set needs PATH=VALUE (e.g. bodies[0].mass=2)");
  const std::string path = assignment.substr(0, equals);
  const std::string text = assignment.substr(equals + 1);
  nlohmann::json value = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = text;  // a bare word: a string

  nlohmann::json* node = &scene;
  std::string walked;
  size_t i = 0;
  while (i < path.size()) {
    if (path[i] == '[') {
      const size_t close = path.find(']', i);
      const std::string digits = close == std::string::npos ? "" : path.substr(i + 1, close - i - 1);
      if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); }))
        throw SceneError(path, "bad index in --set path (use [0], [1], ...)");
      const size_t index = std::stoul(digits);
      if (!node->is_array()) throw SceneError(walked, "is not an array, so " + path + " cannot be set");
      if (index >= node->size())
        throw SceneError(walked, "has " + std::to_string(node->size()) + (node->size() == 1 ? " entry" : " entries") +
                                    ", so " + path + " cannot be set");
      walked += "[" + digits + "]";
      node = &(*node)[index];
      i = close + 1;
    } else {
      if (path[i] == '.') ++i;
      size_t end = i;
      while (end < path.size() && path[end] != '.' && path[end] != '[') ++end;
      const std::string key = path.substr(i, end - i);
      if (key.empty()) throw SceneError(path, "empty field name in --set path");
      if (!node->is_object() && !node->is_null())
        throw SceneError(walked, "is not an object, so " + path + " cannot be set");
      walked += (walked.empty() ? "" : ".") + key;
      node = &(*node)[key];  // creates the field when missing; checking happens later
      i = end;
    }
  }
  *node = value;
}

}  // namespace motus
