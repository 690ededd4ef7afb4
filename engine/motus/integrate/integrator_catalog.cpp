#include "motus/integrate/integrator_catalog.hpp"

#include <iterator>

namespace motus {

namespace {

// In the order of enum class Integrator: info(id) looks an integrator up by its number (checked
// below, at compile time, so that one added in the middle of the enum cannot take another's row).
constexpr IntegratorInfo kIntegrators[] = {
    {Integrator::Euler, "euler", 1, false, false, "explicit Euler: y += h f(t, y)"},
    {Integrator::Midpoint, "midpoint", 2, false, false, "midpoint (RK2): half an Euler step, then the full step with its slope"},
    {Integrator::Rk4, "rk4", 4, false, false, "classic fourth-order Runge-Kutta"},
    {Integrator::Rk4Doubling, "rk4-doubling", 5, true, false, "adaptive RK4 by step doubling, with local extrapolation"},
    {Integrator::Rk45, "rk45", 5, true, false, "Dormand-Prince 5(4), adaptive by atol/rtol"},
    {Integrator::Dop853, "dop853", 8, true, false, "Dormand-Prince 8(5,3), adaptive by atol/rtol: the high-accuracy pair"},
    {Integrator::SymplecticEuler, "symplectic-euler", 1, false, true, "symplectic Euler, velocity first: v += a h; x += v h"},
    {Integrator::SymplecticEulerX, "symplectic-euler-x", 1, false, true, "symplectic Euler, position first: x += v h; v += a(x) h"},
    {Integrator::Verlet, "verlet", 2, false, true, "velocityless (Stormer) Verlet: x_next = 2x - x_prev + a h^2"},
    {Integrator::VelocityVerlet, "velocity-verlet", 2, false, true, "velocity Verlet: kick, drift, kick"},
    {Integrator::Yoshida4, "yoshida4", 4, false, true, "Yoshida's fourth-order symplectic composition of velocity Verlet"},
};

constexpr bool in_the_enums_order() {
  for (size_t i = 0; i < std::size(kIntegrators); ++i)
    if (static_cast<size_t>(kIntegrators[i].id) != i) return false;
  return true;
}
static_assert(in_the_enums_order(), "kIntegrators must list the integrators in the order of enum class Integrator");
static_assert(std::size(kIntegrators) == static_cast<size_t>(Integrator::Yoshida4) + 1,
              "kIntegrators must have a row for every integrator (Yoshida4 is the enum's last)");

}  // namespace

std::span<const IntegratorInfo> all_integrators() { return kIntegrators; }

const IntegratorInfo& info(Integrator id) { return kIntegrators[static_cast<size_t>(id)]; }

std::optional<Integrator> integrator_from_name(std::string_view name) {
  for (const auto& i : all_integrators())
    if (name == i.name) return i.id;
  return std::nullopt;
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const auto& i : all_integrators()) names.emplace_back(i.name);
  return names;
}

std::string first_order_integrator_names() {
  std::vector<std::string> names;
  for (const auto& i : all_integrators())
    if (!i.needs_mechanical) names.emplace_back(i.name);
  std::string list;
  for (size_t k = 0; k < names.size(); ++k) list += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  return list;
}

}  // namespace motus
