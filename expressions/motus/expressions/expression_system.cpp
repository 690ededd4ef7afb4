#include "motus/expressions/expression_system.hpp"

#include <muParser.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

#include "motus/message_number.hpp"

namespace motus::expressions {
namespace {

const mu::Parser& plain_parser() {
  static const mu::Parser parser;  // muparser's own functions and constants, nothing of ours
  return parser;
}

bool is_function(const std::string& name) { return plain_parser().GetFunDef().count(name) > 0; }
bool is_constant(const std::string& name) { return plain_parser().GetConst().count(name) > 0; }

// muparser's message without its "at position N" (we give a 1-based column instead), starting
// with a small letter so that it reads on after "syntax error at column N: ".
std::string plain_message(std::string message) {
  for (const char* tail : {" found at position ", " at expression position ", " at position "}) {
    const auto at = message.find(tail);
    if (at != std::string::npos) {
      auto end = at + std::string(tail).size();
      while (end < message.size() && std::isdigit(static_cast<unsigned char>(message[end]))) ++end;
      message.erase(at, end - at);
    }
  }
  while (!message.empty() && (message.back() == '.' || message.back() == ' ')) message.pop_back();
  if (!message.empty() && message[0] >= 'A' && message[0] <= 'Z' && !(message.size() > 1 && std::isupper(static_cast<unsigned char>(message[1]))))
    message[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(message[0])));
  return message.empty() ? "cannot be parsed" : message;
}

// What stands at `position` of the text: a number as written (1e309, 1.5e), a name, or else one
// character (all of its UTF-8 bytes).
std::string word_at(const std::string& text, size_t position) {
  if (position >= text.size()) return "";
  auto at = [&](size_t i) { return static_cast<unsigned char>(text[i]); };
  auto in_name = [&](size_t i) { return std::isalnum(at(i)) || at(i) == '_'; };
  size_t end = position + 1;
  if (std::isdigit(at(position)) || at(position) == '.') {
    while (end < text.size() && (std::isdigit(at(end)) || at(end) == '.' || at(end) == 'e' || at(end) == 'E' ||
                                 ((at(end) == '+' || at(end) == '-') && (at(end - 1) == 'e' || at(end - 1) == 'E'))))
      ++end;
  } else if (in_name(position)) {
    while (end < text.size() && in_name(end)) ++end;
  } else {
    while (end < text.size() && (at(end) & 0xC0) == 0x80) ++end;
  }
  return text.substr(position, end - position);
}

// The first '=' that is an assignment (x = 3, x += 1), not part of ==, !=, <= or >=; npos if none.
// muparser would assign to the variable, so that one equation changed what the next one sees.
size_t assignment(const std::string& text) {
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '=') continue;
    const char before = i > 0 ? text[i - 1] : ' ', after = i + 1 < text.size() ? text[i + 1] : ' ';
    if (after == '=') {
      ++i;  // ==
      continue;
    }
    if (before == '<' || before == '>' || before == '!') continue;
    return i > 0 && std::string("+-*/").find(before) != std::string::npos ? i - 1 : i;
  }
  return std::string::npos;
}

// The first ',' outside parentheses (two expressions in one), or npos.
size_t top_level_comma(const std::string& text) {
  int depth = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '(') ++depth;
    else if (text[i] == ')') --depth;
    else if (text[i] == ',' && depth <= 0) return i;
  }
  return std::string::npos;
}

}  // namespace

std::string name_problem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name.size() > 100) return "is longer than 100 characters";
  const auto identifier_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  if (!(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') || !std::all_of(name.begin(), name.end(), identifier_char))
    return "is not a name: use a letter or '_' and then letters, digits or '_'";
  if (name == "t") return "is the time, which every equation may use as t";
  if (is_function(name)) return "is one of the functions (" + function_names() + ")";
  if (is_constant(name)) return "is one of the constants (_pi, _e)";
  return "";
}

std::string function_names() {
  std::string list;
  for (const auto& [name, callback] : plain_parser().GetFunDef()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

struct ExpressionSystem::Parsed {
  std::vector<double> values;  // the state as the expressions see it; never resized after binding
  double t = 0;
  std::vector<mu::Parser> parsers;  // one per equation
};

ExpressionSystem::ExpressionSystem(const Equations& e)
    : names_(e.variables), texts_(e.right_hand_sides), parsed_(std::make_unique<Parsed>()) {
  const size_t n = e.variables.size();
  if (n == 0) throw std::invalid_argument("a system needs at least one variable");
  if (e.right_hand_sides.size() != n)
    throw std::invalid_argument("a system needs one equation per variable (" + std::to_string(n) + " variables, " +
                                std::to_string(e.right_hand_sides.size()) + " equations)");
  std::set<std::string> seen;
  for (const auto& name : e.variables)
    if (!name_problem(name).empty() || !seen.insert(name).second) throw std::invalid_argument("variable \"" + name + "\": bad or repeated name");
  for (const auto& [name, value] : e.parameters)
    if (!name_problem(name).empty() || !seen.insert(name).second) throw std::invalid_argument("parameter \"" + name + "\": bad or repeated name");

  std::string known;
  for (const auto& name : e.variables) known += (known.empty() ? "" : ", ") + name;
  known += ", t";
  for (const auto& [name, value] : e.parameters) known += ", " + name;

  auto& p = *parsed_;
  p.values.assign(n, 0.0);
  p.parsers.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const std::string& text = e.right_hand_sides[i];
    const int index = static_cast<int>(i);
    const int end_column = static_cast<int>(text.size()) + 1;
    if (text.find_first_not_of(" \t") == std::string::npos)
      throw EquationError(index, 0, "is empty: give the right-hand side of " + e.variables[i] + "' = ...");
    // muparser reads a C string: a NUL (JSON's \u0000) would end the expression there, silently.
    if (const auto control = std::find_if(text.begin(), text.end(), [](char c) { return c != '\t' && static_cast<unsigned char>(c) < 0x20; });
        control != text.end()) {
      const int column = static_cast<int>(control - text.begin()) + 1;
      throw EquationError(index, column, "a control character (code " + std::to_string(static_cast<int>(*control)) +
                                             ") at column " + std::to_string(column) + ": an expression is one line of text");
    }
    if (const size_t at = assignment(text); at != std::string::npos)
      throw EquationError(index, static_cast<int>(at) + 1,
                          "an assignment at column " + std::to_string(at + 1) +
                              ": an equation is an expression for the derivative (compare with ==)");
    mu::Parser& parser = p.parsers[i];
    try {
      for (size_t k = 0; k < n; ++k) parser.DefineVar(e.variables[k], &p.values[k]);
      parser.DefineVar("t", &p.t);
      for (const auto& [name, value] : e.parameters) parser.DefineConst(name, value);  // folded into the bytecode
      parser.SetExpr(text);
      int results = 0;
      parser.Eval(results);  // parses now, once: every later call runs the bytecode
      if (results != 1) {
        const size_t comma = top_level_comma(text);
        const int column = comma == std::string::npos ? 0 : static_cast<int>(comma) + 1;
        throw EquationError(index, column,
                            "is " + std::to_string(results) + " expressions" +
                                (column ? " (a ',' at column " + std::to_string(column) + ")" : "") +
                                ": an equation is one expression");
      }
    } catch (const mu::Parser::exception_type& error) {
      const int column = std::clamp(error.GetPos() + 1, 1, end_column);
      // (muparser's token is the rest of the expression from there: the word at that column is
      // the one to name.)
      const std::string token = word_at(text, static_cast<size_t>(column - 1));
      if (error.GetCode() == mu::ecUNASSIGNABLE_TOKEN && !token.empty()) {
        const unsigned char first = static_cast<unsigned char>(token[0]);
        if (std::isdigit(first) || first == '.')
          throw EquationError(index, column,
                              "not a number at column " + std::to_string(column) + ": \"" + token +
                                  "\" (a number is written as 1.5 or 2e-3, and is at most about 1.8e308)");
        if (!std::isalpha(first) && first != '_')
          throw EquationError(index, column,
                              "syntax error at column " + std::to_string(column) + ": \"" + token +
                                  "\" is no operator, number or name (operators: + - * / ^, comparisons, && || and ?:; names: "
                                  "ASCII letters, digits and _)");
        if (is_function(token))
          throw EquationError(index, column,
                              "syntax error at column " + std::to_string(column) + ": the function " + token +
                                  " needs its arguments in parentheses, as " + token + "(x)");
        // A name followed by '(' is called: an unknown function, not an unknown variable.
        const size_t after = text.find_first_not_of(" \t", static_cast<size_t>(column - 1) + token.size());
        if (after != std::string::npos && text[after] == '(')
          throw EquationError(index, column,
                              "unknown function \"" + token + "\" at column " + std::to_string(column) +
                                  " (functions: " + function_names() + ")");
        throw EquationError(index, column,
                            "unknown variable \"" + token + "\" at column " + std::to_string(column) + " (known: " +
                                known + "; functions: " + function_names() + ")");
      }
      if (error.GetCode() == mu::ecEMPTY_EXPRESSION)
        throw EquationError(index, 0, "is empty: give the right-hand side of " + e.variables[i] + "' = ...");
      throw EquationError(index, column, "syntax error at column " + std::to_string(column) + ": " + plain_message(error.GetMsg()));
    }
  }
}

ExpressionSystem::~ExpressionSystem() = default;

void ExpressionSystem::derivative(double t, ConstVectorRef y, VectorRef dydt) {
  ++evaluations;
  auto& p = *parsed_;
  p.t = t;
  const size_t n = p.values.size();
  for (size_t i = 0; i < n; ++i) p.values[i] = y[static_cast<Eigen::Index>(i)];
  for (size_t i = 0; i < n; ++i) dydt[static_cast<Eigen::Index>(i)] = p.parsers[i].Eval();
  if (not_finite_.empty() && !dydt.allFinite()) [[unlikely]]
    note_not_finite(t, y, dydt);
}

void ExpressionSystem::note_not_finite(double t, ConstVectorRef y, ConstVectorRef dydt) {
  // Only from a moderate state: one that is already infinite, or so large that a product of a
  // few of its numbers overflows (past 1e100, where three of them make more than 1e300: an
  // unstable step on its way to infinity), makes the equations' values so, and the step is to
  // blame. (Once only: the first is the cause.)
  const double moderate = 1e100;
  if (!(std::abs(t) < moderate) || !(y.cwiseAbs().maxCoeff() < moderate)) return;
  Eigen::Index i = 0;
  while (std::isfinite(dydt[i])) ++i;
  std::string where;
  for (size_t k = 0; k < names_.size(); ++k)
    where += (k ? ", " : "") + names_[k] + " = " + message_number(y[static_cast<Eigen::Index>(k)]);
  not_finite_ = "the equation " + names_[static_cast<size_t>(i)] + "' = " + texts_[static_cast<size_t>(i)] + " gave " +
                message_number(dydt[i]) + " at t = " + message_number(t) + " where " + where +
                " (outside a function's domain? a division by zero?)";
}

}  // namespace motus::expressions
