#pragma once
// The first-order systems a scene can name in `system.type`, with their parameters
// and defaults. The scene loader checks parameters against this list; `motus list`
// prints it.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "motus/systems/first_order_system.hpp"

namespace motus {

struct ParameterInfo {
  std::string name;
  double default_value;
  std::string meaning;
};

struct SystemInfo {
  std::string type;
  std::string description;
  std::vector<std::string> variables;
  std::vector<ParameterInfo> parameters;
  std::function<std::unique_ptr<FirstOrderSystem>(const std::map<std::string, double>&)> make;
  // What each variable is, with its unit ("population (people)"), for legends and tables;
  // empty where the name says it all (x, y, z).
  std::vector<std::string> meanings = {};
  // What the independent variable counts: seconds, or World2's calendar years.
  std::string time_unit = "s";
};

const std::vector<SystemInfo>& first_order_systems();
const SystemInfo* find_first_order_system(std::string_view type);

}  // namespace motus
