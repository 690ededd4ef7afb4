#pragma once
// Loading students' plug-ins (--plugin FILE.so, repeatable) and finding what they bring:
// integrators under PLUGIN:NAME wherever --integrator is taken, a collision response and a
// constraint projection that replace motus's own for a run (see docs/architecture.md).
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "motus/external/external_parts.hpp"
#include "motus/integrate/method.hpp"
#include "motus/plugin/plugin_abi.hpp"

namespace motus {

// A plug-in that cannot be used: one line naming the file and what is wrong.
class PluginError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct LoadedPlugin {
  std::string file;         // as given
  std::string name;         // the plug-in's own name ("student")
  std::string description;
  const PluginEntry* entry = nullptr;
  std::vector<std::string> integrator_names;  // "student:euler", ...
};

class PluginSet {
public:
  PluginSet() = default;
  PluginSet(const PluginSet&) = delete;
  PluginSet& operator=(const PluginSet&) = delete;
  ~PluginSet();

  // Loads a plug-in. Throws PluginError when the file is missing or not a shared library,
  // has no entry point motus_plugin, was built for another plug-in interface, has no name or
  // a name another loaded plug-in has, brings an integrator twice or one named like a
  // built-in, or brings a collision response or constraint projection another one brings.
  void load(const std::string& file);

  const std::vector<LoadedPlugin>& plugins() const { return plugins_; }
  bool empty() const { return plugins_.empty(); }

  // The integrator called `name` ("student:euler"), if a loaded plug-in brings it.
  std::optional<Method> integrator(const std::string& name) const;
  // Every loaded integrator, plug-in by plug-in.
  std::vector<Method> integrators() const;
  // The collision response and constraint projection the plug-ins bring (null where none does).
  ExternalParts parts() const;
  // The loaded plug-in that brings them, for the name of the "student" engine column ("" for none).
  std::string parts_owner() const;

private:
  std::vector<LoadedPlugin> plugins_;
  std::vector<void*> handles_;
};

// From now until the process ends, a crash (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) prints
// one line naming the plug-in whose code was running — or, when the crash was elsewhere,
// the plug-ins that were loaded — before the process dies of the signal as it would have.
void report_plugin_crashes(const PluginSet& plugins);
// Until report_plugin_crashes: a crash, or an exception out of a global's constructor, while
// `file` is being loaded prints one line naming it (its code runs as soon as it is opened).
void report_crashes_while_loading(const std::string& file);

}  // namespace motus
