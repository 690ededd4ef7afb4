#include "motus/compare/backends/backend.hpp"

#include "motus/compare/backends/motus_backend.hpp"

namespace motus::compare {

std::vector<std::string> backend_names() {
  return {"motus", "box2d", "bullet"};
}

std::unique_ptr<Backend> make_backend(const std::string& name) {
  if (name == "motus") return std::make_unique<MotusBackend>();
  if (name == "box2d" || name == "bullet") return make_peer_backend(name);
  throw std::invalid_argument("unknown engine \"" + name + "\"");
}

}  // namespace motus::compare
