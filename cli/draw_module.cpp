#include "draw_module.hpp"

#include <dlfcn.h>

#include <filesystem>

#include "cli_common.hpp"

namespace fs = std::filesystem;

namespace motus::cli {
namespace {

const draw::Api& load() {
  std::string tried;
  for (const auto& path : module_candidates("MOTUS_DRAW_MODULE", MOTUS_DRAW_MODULE_NAME, MOTUS_DRAW_MODULE_INSTALLED)) {
    if (!fs::exists(path)) {
      tried += (tried.empty() ? "" : ", ") + path;
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw InputError(path + ": cannot load the drawing module: " + dlerror());
    using Entry = const draw::Api* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, draw::kEntryPoint));
    if (!entry) throw InputError(path + ": is not motus's drawing module (no " + draw::kEntryPoint + ")");
    const draw::Api* api = entry();
    if (!api || api->version != draw::kApiVersion)
      throw InputError(path + ": drawing module of another motus build (interface " +
                       std::to_string(api ? api->version : 0) + ", this motus needs " +
                       std::to_string(draw::kApiVersion) + "); rebuild or reinstall motus");
    return *api;
  }
  throw InputError("the drawing module " MOTUS_DRAW_MODULE_NAME " was not found (looked for " + tried +
                   "); build the target motus-draw, or set MOTUS_DRAW_MODULE");
}

}  // namespace

const draw::Api& draw_module() {
  static const draw::Api& api = load();
  return api;
}

}  // namespace motus::cli
