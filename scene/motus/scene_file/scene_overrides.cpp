#include "motus/scene_file/scene_overrides.hpp"

#include <algorithm>
#include <cctype>

#include "motus/scene_error.hpp"

namespace motus {

bool valid_utf8(const std::string& s) {
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    const int length = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (length == 0 || (length > 1 && c < 0xC2) || i + static_cast<size_t>(length) > s.size()) return false;
    for (int k = 1; k < length; ++k)
      if ((static_cast<unsigned char>(s[i + static_cast<size_t>(k)]) & 0xC0) != 0x80) return false;
    i += static_cast<size_t>(length);
  }
  return true;
}

void apply_override(nlohmann::json& scene, const std::string& assignment) {
  const auto equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0)
    throw SceneError(assignment, "--set needs PATH=VALUE (e.g. bodies[0].mass=2)");
  const std::string path = assignment.substr(0, equals);
  const std::string text = assignment.substr(equals + 1);
  nlohmann::json value;
  try {
    value = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    // A number too large for a double (1e999) is what it is in a scene file, not a word.
    if (e.id == 406) throw SceneError(path, "number overflow: " + text + " (numbers must be finite)");
    value = text;  // a bare word: a string
  }
  // A scene file's strings are checked by the JSON parser; the command line's are not.
  if (!valid_utf8(text)) throw SceneError(path, "the value given by --set is not valid UTF-8");

  nlohmann::json* node = &scene;
  std::string walked;
  size_t i = 0;
  while (i < path.size()) {
    // A name starts the path or follows a '.'; an index follows a name or an index (".dt" and
    // "bodies[0]mass" are no paths, whatever they could be taken for).
    if (i == 0 && path[i] == '.') throw SceneError(path, "empty field name in --set path");
    if (i > 0 && path[i - 1] == ']' && path[i] != '.' && path[i] != '[')
      throw SceneError(path, "a '.' must come between an index and a field name in --set path (e.g. bodies[0].mass)");
    if (path[i] == '[') {
      const size_t close = path.find(']', i);
      const std::string digits = close == std::string::npos ? "" : path.substr(i + 1, close - i - 1);
      if (digits.empty() || !std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c); }))
        throw SceneError(path, "bad index in --set path (use [0], [1], ...)");
      if (digits.size() > 9) throw SceneError(path, "index " + digits.substr(0, 12) + (digits.size() > 12 ? "…" : "") +
                                                        " in --set path is too large");
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
