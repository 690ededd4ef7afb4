// motus-peers.so: Box2D and Bullet behind compare::Backend, for the `motus` command (peers_api.hpp).
#include "peers/peers_api.hpp"

namespace {

motus::compare::Backend* make(const char* name) {
  const std::string engine(name);
  if (engine != "box2d" && engine != "bullet") return nullptr;
  return motus::compare::make_peer_backend(engine).release();
}

}  // namespace

extern "C" __attribute__((visibility("default"))) const motus::peers::Api* motus_peers_api() {
  static const motus::peers::Api api{motus::peers::kApiVersion, make};
  return &api;
}
