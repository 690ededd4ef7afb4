// The scene loader's way to an ExpressionSystem, with muparser linked in (the `motus` command
// has its own: see expression_system.hpp).
#include "motus/expressions/expression_system.hpp"

namespace motus::expressions {

std::unique_ptr<FirstOrderSystem> make_expression_system(const Equations& equations) {
  return std::make_unique<ExpressionSystem>(equations);
}

}  // namespace motus::expressions
