#pragma once
// The boundary between `motus` and its expressions module, motus-expressions.so.
//
// A scene's `equations` system is parsed by muparser (and the libgomp it needs), which no
// other scene and no other command uses, so they live in a module that `motus` loads (dlopen)
// when a scene first has an equations system, and every command starts without them (see
// docs/architecture.md).
//
// The module is built from this tree with the same compiler, as the peers module is: a system made
// in it is used and deleted through its virtual functions as one made here, and an
// EquationError it throws is caught as any other; kApiVersion guards against a module left over
// from another build.
#include <string>

#include "motus/expressions/expression_system.hpp"

namespace motus::expressions_module {

constexpr int kApiVersion = 1;
// The function the module exports (extern "C", so dlsym finds it by this name).
constexpr const char* kEntryPoint = "motus_expressions_api";

struct Api {
  int version;
  // expressions::name_problem.
  std::string (*name_problem)(const std::string& name);
  // A new expressions::ExpressionSystem, the caller's to delete; throws as its constructor does.
  FirstOrderSystem* (*make)(const expressions::Equations& equations);
};

}  // namespace motus::expressions_module
