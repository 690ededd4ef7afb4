#include "motus/systems/system_catalog.hpp"

#include "motus/systems/attractors.hpp"
#include "motus/systems/world2.hpp"

namespace motus {

const std::vector<SystemInfo>& first_order_systems() {
  static const std::vector<SystemInfo> list = {
      {"lorenz", "Lorenz attractor: x' = sigma(y - x), y' = x(rho - z) - y, z' = xy - beta z", {"x", "y", "z"},
       {{"sigma", 10, "Prandtl number"}, {"rho", 28, "Rayleigh number"}, {"beta", 8.0 / 3, "geometric factor"}},
       [](const auto& p) { return std::make_unique<Lorenz>(p.at("sigma"), p.at("rho"), p.at("beta")); }},
      {"rossler", "Rossler attractor: x' = -y - z, y' = x + ay, z' = b + z(x - c)", {"x", "y", "z"},
       {{"a", 0.2, ""}, {"b", 0.2, ""}, {"c", 5.7, ""}},
       [](const auto& p) { return std::make_unique<Rossler>(p.at("a"), p.at("b"), p.at("c")); }},
      {"chen", "Chen attractor: x' = a(y - x), y' = (c - a)x - xz + cy, z' = xy - bz", {"x", "y", "z"},
       {{"a", 35, ""}, {"b", 3, ""}, {"c", 28, ""}},
       [](const auto& p) { return std::make_unique<Chen>(p.at("a"), p.at("b"), p.at("c")); }},
      {"thomas", "Thomas' cyclically symmetric attractor: x' = sin y - bx, ...", {"x", "y", "z"},
       {{"b", 0.208186, "damping"}},
       [](const auto& p) { return std::make_unique<Thomas>(p.at("b")); }},
      {"aizawa", "Aizawa attractor", {"x", "y", "z"},
       {{"a", 0.95, ""}, {"b", 0.7, ""}, {"c", 0.6, ""}, {"d", 3.5, ""}, {"e", 0.25, ""}, {"f", 0.1, ""}},
       [](const auto& p) {
         return std::make_unique<Aizawa>(p.at("a"), p.at("b"), p.at("c"), p.at("d"), p.at("e"), p.at("f"));
       }},
      world2_system_info(),
  };
  return list;
}

const SystemInfo* find_first_order_system(std::string_view type) {
  for (const auto& s : first_order_systems())
    if (s.type == type) return &s;
  return nullptr;
}

}  // namespace motus
