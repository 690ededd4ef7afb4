#pragma once
// The boundary between `motus` and its peers module, motus-peers.so.
//
// Box2D and Bullet are four shared libraries (Box2D's one, Bullet's three; ~2 MB) that only `motus compare` and `motus bench
// precision --peers` use, so they live in a module that `motus` loads (dlopen) when a command
// first asks for a peer, and every other command starts without them (see docs/architecture.md).
//
// The module is built from this tree with the same compiler, so a Backend made in it is used
// and deleted through its virtual functions as one made here, and its Unsupported (a scene it
// cannot run) is caught as any other; kApiVersion guards against a module left over from
// another build.
#include "motus/compare/backends/backend.hpp"

namespace motus::peers {

constexpr int kApiVersion = 1;
// The function the module exports (extern "C", so dlsym finds it by this name).
constexpr const char* kEntryPoint = "motus_peers_api";

struct Api {
  int version;
  // A new "box2d" or "bullet" backend, the caller's to delete; nullptr for another name.
  compare::Backend* (*make)(const char* name);
};

}  // namespace motus::peers
