#include "motus/forces/force_set.hpp"

#include <algorithm>

namespace motus {

double ForceSet::potential(int d, const Vector& m, ConstVectorRef x) const {
  double u = 0;
  for (const auto& f : gravity) u += f.potential(d, m, x);
  for (const auto& f : springs) u += f.potential(d, x);
  for (const auto& f : central_gravity) u += f.potential(d, m, x);
  for (const auto& f : mutual_gravity) u += f.potential(d, m, x);
  for (const auto& f : pendulums) u += f.potential(d, m, x);
  return u;
}

bool ForceSet::acts() const {
  const auto any = [](const auto& forces, auto acts) { return std::any_of(forces.begin(), forces.end(), acts); };
  return any(gravity, [](const UniformGravity& f) { return f.g[0] != 0 || f.g[1] != 0 || f.g[2] != 0; }) ||
         any(springs, [](const Spring& f) { return f.stiffness != 0 || f.damping != 0; }) ||
         any(drag, [](const LinearDrag& f) { return f.coefficient != 0; }) ||
         any(central_gravity, [](const CentralGravity& f) { return f.mu != 0; }) ||
         any(mutual_gravity, [](const MutualGravity& f) { return f.G != 0; }) ||
         any(pendulums, [](const PendulumTorque& f) { return f.g != 0; });
}

bool ForceSet::empty() const {
  return gravity.empty() && springs.empty() && drag.empty() && central_gravity.empty() &&
         mutual_gravity.empty() && pendulums.empty();
}

}  // namespace motus
