// The `motus` command's make_peer_backend: Box2D and Bullet from motus-peers.so, loaded when a
// command first asks for a peer (compare/motus/compare/backends/backend.hpp says why).
#include <dlfcn.h>

#include <filesystem>

#include "cli_common.hpp"
#include "peers/peers_api.hpp"

namespace fs = std::filesystem;

namespace motus {
namespace {

const peers::Api& load() {
  std::string tried;
  for (const auto& path : cli::module_candidates("MOTUS_PEERS_MODULE", MOTUS_PEERS_MODULE_NAME, MOTUS_PEERS_MODULE_INSTALLED)) {
    if (!fs::exists(path)) {
      tried += (tried.empty() ? "" : ", ") + path;
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw cli::InputError(path + ": cannot load the peers module: " + dlerror());
    using Entry = const peers::Api* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, peers::kEntryPoint));
    if (!entry) throw cli::InputError(path + ": is not motus's peers module (no " + peers::kEntryPoint + ")");
    const peers::Api* api = entry();
    if (!api || api->version != peers::kApiVersion)
      throw cli::InputError(path + ": peers module of another motus build (interface " +
                            std::to_string(api ? api->version : 0) + ", this motus needs " +
                            std::to_string(peers::kApiVersion) + "); rebuild or reinstall motus");
    return *api;
  }
  throw cli::InputError("the peers module " MOTUS_PEERS_MODULE_NAME " (Box2D and Bullet) was not found (looked for " +
                        tried + "); build the target motus-peers, or set MOTUS_PEERS_MODULE");
}

}  // namespace

std::unique_ptr<compare::Backend> compare::make_peer_backend(const std::string& name) {
  static const peers::Api& api = load();
  compare::Backend* backend = api.make(name.c_str());
  if (!backend) throw std::invalid_argument("unknown engine \"" + name + "\"");
  return std::unique_ptr<compare::Backend>(backend);
}

}  // namespace motus
