// motus-expressions.so: the scene file's `equations` systems (muparser), for the `motus` command
// (expressions_api.hpp).
#include "expressions/expressions_api.hpp"

namespace {

std::string name_problem(const std::string& name) { return motus::expressions::name_problem(name); }

motus::FirstOrderSystem* make(const motus::expressions::Equations& equations) {
  return new motus::expressions::ExpressionSystem(equations);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) const motus::expressions_module::Api* motus_expressions_api() {
  static const motus::expressions_module::Api api{motus::expressions_module::kApiVersion, name_problem, make};
  return &api;
}
