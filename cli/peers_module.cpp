// The `motus` command's make_peer_backend: Box2D and Bullet from motus-peers.so, loaded when a
// command first asks for a peer (compare/motus/compare/backends/backend.hpp says why).
#include "module_loader.hpp"
#include "peers/peers_api.hpp"

namespace motus {
namespace {

const peers::Api& load() {
  return cli::load_module<peers::Api>("MOTUS_PEERS_MODULE", MOTUS_PEERS_MODULE_NAME, MOTUS_PEERS_MODULE_INSTALLED,
                                      peers::kEntryPoint, peers::kApiVersion, "peers module (Box2D and Bullet)",
                                      "motus-peers");
}

}  // namespace

std::unique_ptr<compare::Backend> compare::make_peer_backend(const std::string& name) {
  static const peers::Api& api = load();
  compare::Backend* backend = api.make(name.c_str());
  if (!backend) throw std::invalid_argument("unknown engine \"" + name + "\"");
  return std::unique_ptr<compare::Backend>(backend);
}

}  // namespace motus
