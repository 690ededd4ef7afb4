// The `motus` command's make_expression_system and name_problem: muparser from
// motus-expressions.so, loaded when a scene first has an equations system
// (expressions/motus/expressions/expression_system.hpp says why).
#include "expressions/expressions_api.hpp"
#include "module_loader.hpp"

namespace motus {
namespace {

const expressions_module::Api& load() {
  static const expressions_module::Api& api = cli::load_module<expressions_module::Api>(
      "MOTUS_EXPRESSIONS_MODULE", MOTUS_EXPRESSIONS_MODULE_NAME, MOTUS_EXPRESSIONS_MODULE_INSTALLED,
      expressions_module::kEntryPoint, expressions_module::kApiVersion, "expressions module (muparser)",
      "motus-expressions");
  return api;
}

}  // namespace

std::string expressions::name_problem(const std::string& name) { return load().name_problem(name); }

std::unique_ptr<FirstOrderSystem> expressions::make_expression_system(const Equations& equations) {
  return std::unique_ptr<FirstOrderSystem>(load().make(equations));
}

}  // namespace motus
