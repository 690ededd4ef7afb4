#pragma once
// What a fuzzer's bytes mean: a scene file, then (after each NUL byte) one --set override.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace motus::fuzz {

struct Input {
  std::string scene;
  std::vector<std::string> overrides;
};

inline Input split(const uint8_t* data, size_t size) {
  Input input;
  std::string* current = &input.scene;
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == 0) {
      if (input.overrides.size() == 8) break;  // a few are enough to reach every path
      input.overrides.emplace_back();
      current = &input.overrides.back();
    } else {
      current->push_back(static_cast<char>(data[i]));
    }
  }
  return input;
}

}  // namespace motus::fuzz
