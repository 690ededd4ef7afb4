#pragma once
// What is wrong with a scene, and where: the field path (e.g. "bodies[2].mass") and a
// message. The loader adds the file name; the command line prints one line and exits 2.
#include <stdexcept>
#include <string>

namespace motus {

class SceneError : public std::runtime_error {
public:
  SceneError(std::string field, const std::string& message)
      : std::runtime_error(message), field_(std::move(field)) {}
  const std::string& field() const { return field_; }

private:
  std::string field_;
};

}  // namespace motus
