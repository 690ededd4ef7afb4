#include "motus/compare/backends/backend.hpp"
#include "motus/compare/backends/box2d_backend.hpp"
#include "motus/compare/backends/bullet_backend.hpp"

namespace motus::compare {

// The peers, linked in. (The `motus` command defines its own make_peer_backend, which loads
// them from its module motus-peers.so when a command first runs one: see backend.hpp.)
std::unique_ptr<Backend> make_peer_backend(const std::string& name) {
  if (name == "box2d") return std::make_unique<Box2dBackend>();
  if (name == "bullet") return std::make_unique<BulletBackend>();
  throw std::invalid_argument("unknown engine \"" + name + "\"");
}

}  // namespace motus::compare
