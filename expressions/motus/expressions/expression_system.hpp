#pragma once
// A first-order system y' = f(t, y) whose right-hand sides are written as expressions: the
// scene file's "equations" system (docs/scene-format.md). The expressions are parsed once, when
// the system is made, by muparser (its bytecode then runs at every evaluation); muparser's
// headers stay in the .cpp. Every Runge–Kutta method runs it like any other FirstOrderSystem.
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "motus/systems/first_order_system.hpp"

namespace motus::expressions {

struct Equations {
  std::vector<std::string> variables;                      // the state, in order
  std::vector<std::pair<std::string, double>> parameters;  // named constants of the expressions
  std::vector<std::string> right_hand_sides;               // right_hand_sides[i] is variables[i]'
};

// Why an equation cannot be used: which one (its index), where (a 1-based column in its text;
// 0 when no column applies) and what is wrong, as one line.
class EquationError : public std::runtime_error {
public:
  EquationError(int equation, int column, const std::string& message)
      : std::runtime_error(message), equation(equation), column(column) {}
  int equation, column;
};

// "" when `name` can be a variable or a parameter; else why not: it must look like an
// identifier (a letter or '_', then letters, digits, '_'), and it must not be "t" (the time) or
// one of muparser's functions and constants (sin, exp, _pi, ...).
std::string name_problem(const std::string& name);

// muparser's built-in functions, for messages ("abs, acos, ...").
std::string function_names();

class ExpressionSystem final : public FirstOrderSystem {
public:
  // Parses every right-hand side; throws EquationError for the first one that is not a single
  // expression in the variables, t and the parameters. The names must be valid (name_problem)
  // and distinct: std::invalid_argument otherwise.
  explicit ExpressionSystem(const Equations& equations);
  ~ExpressionSystem() override;
  ExpressionSystem(const ExpressionSystem&) = delete;
  ExpressionSystem& operator=(const ExpressionSystem&) = delete;

  int size() const override { return static_cast<int>(names_.size()); }
  void derivative(double t, ConstVectorRef y, VectorRef dydt) override;
  std::vector<std::string> variable_names() const override { return names_; }
  std::string why_not_finite() const override { return not_finite_; }

private:
  void note_not_finite(double t, ConstVectorRef y, ConstVectorRef dydt);
  struct Parsed;
  std::vector<std::string> names_;
  std::vector<std::string> texts_;  // the right-hand sides as written, for messages
  std::string not_finite_;          // the first equation that gave a NaN or an infinity from a moderate state
  std::unique_ptr<Parsed> parsed_;
};

// A new ExpressionSystem for `equations`, as the scene loader makes them: motus::expressions
// defines it with muparser linked in (make_expression_system.cpp: tests, benchmarks and the
// installed library use it). The `motus` command defines it, and name_problem, again
// (cli/expressions_module.cpp): they load muparser, in the module motus-expressions.so, only when a
// scene has an equations system, so that every other command starts without it. (The command's
// definitions are linked before the library's, whose objects are then never taken from the archive.)
std::unique_ptr<FirstOrderSystem> make_expression_system(const Equations& equations);

}  // namespace motus::expressions
