#pragma once
// Loading one of the `motus` command's modules (motus-draw.so, motus-peers.so) when a command
// first needs it: its versioned table of functions, from its extern "C" entry point.
#include <dlfcn.h>

#include <filesystem>
#include <string>

#include "cli_common.hpp"

namespace motus::cli {

// The table of the first of module_candidates(env_var, name, installed) that exists (an Api whose
// `version` must be `version`). Throws InputError (one line, exit 2) naming `what` ("drawing
// module") when none is found (`target`: the CMake target that builds it), when it cannot be
// loaded or has no `entry_point`, or when it was built for another interface version.
template <class Api>
const Api& load_module(const char* env_var, const std::string& name, const std::string& installed,
                       const char* entry_point, int version, const std::string& what, const std::string& target) {
  std::string tried;
  for (const auto& path : module_candidates(env_var, name, installed)) {
    if (!std::filesystem::exists(path)) {
      tried += (tried.empty() ? "" : ", ") + path;
      continue;
    }
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw InputError(path + ": cannot load the " + what + ": " + dlerror());
    using Entry = const Api* (*)();
    auto entry = reinterpret_cast<Entry>(dlsym(handle, entry_point));
    if (!entry) throw InputError(path + ": is not motus's " + what + " (no " + entry_point + ")");
    const Api* api = entry();
    if (!api || api->version != version)
      throw InputError(path + ": " + what + " of another motus build (interface " + std::to_string(api ? api->version : 0) +
                       ", this motus needs " + std::to_string(version) + "); rebuild or reinstall motus");
    return *api;
  }
  throw InputError("the " + what + " " + name + " was not found (looked for " + tried + "); build the target " + target +
                   ", or set " + env_var);
}

}  // namespace motus::cli
