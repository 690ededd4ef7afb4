#pragma once
// The integrators by their command-line names, and what each one is.
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace motus {

enum class Integrator {
  Euler,
  Midpoint,
  Rk4,
  Rk4Doubling,
  Rk45,
  Dop853,
  SymplecticEuler,
  SymplecticEulerX,
  Verlet,
  VelocityVerlet,
  Yoshida4,  // the last (integrator_catalog.cpp checks that its table has a row for each, in this order)
};

struct IntegratorInfo {
  Integrator id;
  const char* name;         // command-line name
  int order;                // global order of accuracy
  bool adaptive;            // chooses its own steps from a tolerance
  bool needs_mechanical;    // the symplectic family works on x and v, not on y
  const char* description;  // one line
};

std::span<const IntegratorInfo> all_integrators();
const IntegratorInfo& info(Integrator id);
std::optional<Integrator> integrator_from_name(std::string_view name);
// {"euler", "midpoint", ...}: the names, in all_integrators()'s order (for error messages).
std::vector<std::string> integrator_names();
// "euler, midpoint, rk4, rk4-doubling, rk45 or dop853": the built-in methods that can step a
// first-order system (for the errors that send a symplectic method away from one).
std::string first_order_integrator_names();

}  // namespace motus
