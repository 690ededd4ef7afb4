#pragma once
// What is wrong with a scene, and where: the field path (e.g. "bodies[2].mass") and a
// message. The loader adds the file name; the command line prints one line and exits 2.
#include <stdexcept>
#include <string>

namespace motus {

// A NUL the user wrote ("\u0000" in a key or a string) is kept as those six characters: what()
// is a C string, and the message ended at it ("integrator: unknown integrator \"", and no more).
inline std::string without_nul(std::string text) {
  for (size_t at = text.find('\0'); at != std::string::npos; at = text.find('\0', at + 6)) text.replace(at, 1, "\\u0000");
  return text;
}

class SceneError : public std::runtime_error {
public:
  SceneError(std::string field, const std::string& message)
      : std::runtime_error(without_nul(message)), field_(without_nul(std::move(field))) {}
  const std::string& field() const { return field_; }

private:
  std::string field_;
};

}  // namespace motus
