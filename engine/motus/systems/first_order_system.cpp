#include "motus/systems/first_order_system.hpp"

namespace motus {

std::vector<std::string> FirstOrderSystem::variable_names() const {
  std::vector<std::string> names;
  for (int i = 0; i < size(); ++i) {
    std::string name = "y";  // (not "y" + to_string(i): GCC 12 warns falsely on that, PR105651)
    name += std::to_string(i);
    names.push_back(name);
  }
  return names;
}

}  // namespace motus
