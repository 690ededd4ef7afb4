#pragma once
// The one entry point of a motus plug-in: a shared library that exports
//   extern "C" const motus::PluginEntry* motus_plugin();
// and says in it what it brings — integrators, a collision response, a constraint
// projection — as the engine's outside parts (motus/external/external_parts.hpp).
// motus refuses an entry of another abi_version with one line: rebuild the plug-in.
#include "motus/external/external_parts.hpp"

namespace motus {

// Changes whenever this struct or external_parts.hpp does.
constexpr int kPluginAbiVersion = 100 + kExternalPartsVersion;
constexpr const char* kPluginEntryPoint = "motus_plugin";

struct PluginEntry {
  int abi_version;          // kPluginAbiVersion when it was built
  const char* name;         // "student": its integrators are "student:euler", its engine column "student"
  const char* description;  // one line
  int integrator_count;
  const ExternalIntegrator* integrators;
  const ExternalCollisionRules* collisions;    // or null
  const ExternalConstraintRules* constraints;  // or null
};

}  // namespace motus
