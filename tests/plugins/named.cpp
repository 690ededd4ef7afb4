// A plug-in whose name motus refuses, built once per case (NAME_CASE): 1 "Box2D", a name a reader
// could not tell from the built-in engine's column; 2 a name with a line break and a terminal's
// colour code, which broke list's lines and compare's table.
#include "motus/plugin/plugin_abi.hpp"

#if NAME_CASE == 1
#define PLUGIN_NAME "Box2D"
#else
#define PLUGIN_NAME "stu\ndent\x1b[31m"
#endif

extern "C" __attribute__((visibility("default"))) const motus::PluginEntry* motus_plugin() {
  static const motus::PluginEntry entry{motus::kPluginAbiVersion, PLUGIN_NAME, "a name to refuse", 0, nullptr, nullptr, nullptr};
  return &entry;
}
