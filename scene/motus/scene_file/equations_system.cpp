#include "motus/scene_file/equations_system.hpp"

#include <algorithm>
#include <memory>

#include "motus/expressions/expression_system.hpp"

namespace motus {

FirstOrderDescription read_equations_system(JsonFields& system) {
  FirstOrderDescription s;
  s.type = "equations";
  expressions::Equations spec;

  // "variables": the state's names, in order.
  if (!system.has("variables"))
    system.fail("variables", "missing (required): the names of the state's variables, e.g. [\"x\", \"v\"]");
  const nlohmann::json& variables = system.raw().at("variables");
  system.use("variables");
  const std::string variables_path = system.path_of("variables");
  if (!variables.is_array()) system.fail("variables", "must be an array of names, not " + json_type_name(variables));
  if (variables.empty()) system.fail("variables", "needs at least one variable");
  if (variables.size() > static_cast<size_t>(kMaxEquations))
    system.fail("variables", std::to_string(variables.size()) + " variables is more than " + std::to_string(kMaxEquations) +
                                 ", the limit of an equations system");
  for (size_t i = 0; i < variables.size(); ++i) {
    const std::string item = variables_path + "[" + std::to_string(i) + "]";
    if (!variables[i].is_string()) throw SceneError(item, "must be a string (a name), not " + json_type_name(variables[i]));
    const std::string name = variables[i].get<std::string>();
    if (const std::string problem = expressions::name_problem(name); !problem.empty())
      throw SceneError(item, "\"" + name + "\" " + problem);
    if (std::find(spec.variables.begin(), spec.variables.end(), name) != spec.variables.end())
      throw SceneError(item, "\"" + name + "\" is listed twice");
    spec.variables.push_back(name);
  }
  std::string listed;
  for (const auto& v : spec.variables) listed += (listed.empty() ? "" : ", ") + v;

  // "parameters": named constants, any names that are not variables.
  if (system.has("parameters")) {
    JsonFields parameters = system.object("parameters");
    for (const auto& name : parameters.keys()) {
      if (const std::string problem = expressions::name_problem(name); !problem.empty())
        parameters.fail(name, "\"" + name + "\" " + problem);
      if (std::find(spec.variables.begin(), spec.variables.end(), name) != spec.variables.end())
        parameters.fail(name, "\"" + name + "\" is a variable; a parameter needs a name of its own");
      const double value = parameters.number(name);
      spec.parameters.emplace_back(name, value);
      s.parameters[name] = value;
    }
  }

  // "equations": one right-hand side per variable, no more and no fewer.
  if (!system.has("equations"))
    system.fail("equations", "missing (required): one expression per variable, e.g. {\"x\": \"v\", \"v\": \"-x\"}");
  JsonFields equations = system.object("equations");
  for (const auto& key : equations.keys())
    if (std::find(spec.variables.begin(), spec.variables.end(), key) == spec.variables.end())
      equations.fail(key, "no variable is called \"" + key + "\" (variables: " + listed + "): one equation per variable");
  for (const auto& name : spec.variables) {
    if (!equations.has(name))
      equations.fail(name, "missing: every variable needs its equation, the right-hand side of " + name + "' = ...");
    spec.right_hand_sides.push_back(equations.string(name));
    // muparser refuses a longer one as "expression too long" at column 1: say what the limit is.
    if (spec.right_hand_sides.back().size() > 10000)
      equations.fail(name, "the expression has " + std::to_string(spec.right_hand_sides.back().size()) +
                               " characters; at most 10,000");
  }
  try {
    expressions::make_expression_system(spec);  // the first problem, with its column
  } catch (const expressions::EquationError& e) {
    equations.fail(spec.variables[static_cast<size_t>(e.equation)], e.what());
  }

  s.initial = system.numbers("initial", static_cast<int>(spec.variables.size()));
  system.reject_unknown();
  s.variables = spec.variables;
  s.make = [spec]() { return expressions::make_expression_system(spec); };
  return s;
}

}  // namespace motus
