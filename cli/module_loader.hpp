#pragma once
// Loading one of the `motus` command's modules (motus-draw.so, motus-peers.so, motus-expressions.so) when a command
// first needs it: its versioned table of functions, from its extern "C" entry point.
#include <dlfcn.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <new>
#include <string>

#include "cli_common.hpp"
#include "locations.hpp"

namespace motus::cli {

// Whether dlopen's `error` is memory running out (a limit such as `ulimit -v`: "libLLVM-15.so.1: failed
// to map segment from shared object", which says no more): the run ran out of memory, it is not bad
// input. (The same words for a file on a noexec mount: so only when 256 MB cannot be mapped either.)
inline bool out_of_address_space(const std::string& error) {
  if (error.find("failed to map segment") == std::string::npos && error.find("cannot map zero-fill") == std::string::npos &&
      error.find(std::strerror(ENOMEM)) == std::string::npos)
    return false;
  constexpr size_t kProbe = size_t{256} << 20;
  void* probe = ::mmap(nullptr, kProbe, PROT_NONE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
  if (probe == MAP_FAILED) return true;
  ::munmap(probe, kProbe);
  return false;
}

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
    if (!handle) {
      const std::string why = dlerror();
      if (out_of_address_space(why)) throw std::bad_alloc();
      throw InputError(path + ": cannot load the " + what + ": " + why);
    }
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
