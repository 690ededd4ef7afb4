// A plug-in built for another plug-in interface: its entry says abi_version 1.
#include "motus/plugin/plugin_abi.hpp"

extern "C" __attribute__((visibility("default"))) const motus::PluginEntry* motus_plugin() {
  static const motus::PluginEntry entry{1, "old", "built for interface 1", 0, nullptr, nullptr, nullptr};
  return &entry;
}
