#include "motus/forces/force_set.hpp"

namespace motus {

void ForceSet::add_forces(double /*t*/, int d, const Vector& m, ConstVectorRef x, ConstVectorRef v,
                          VectorRef F) const {
  for (const auto& f : gravity) f.add_forces(d, m, x, F);
  for (const auto& f : springs) f.add_forces(d, x, v, F);
  for (const auto& f : drag) f.add_forces(d, v, F);
  for (const auto& f : central_gravity) f.add_forces(d, m, x, F);
  for (const auto& f : mutual_gravity) f.add_forces(d, m, x, F);
  for (const auto& f : pendulums) f.add_forces(d, m, x, F);
}

double ForceSet::potential(int d, const Vector& m, ConstVectorRef x) const {
  double u = 0;
  for (const auto& f : gravity) u += f.potential(d, m, x);
  for (const auto& f : springs) u += f.potential(d, x);
  for (const auto& f : central_gravity) u += f.potential(d, m, x);
  for (const auto& f : mutual_gravity) u += f.potential(d, m, x);
  for (const auto& f : pendulums) u += f.potential(d, m, x);
  return u;
}

bool ForceSet::empty() const {
  return gravity.empty() && springs.empty() && drag.empty() && central_gravity.empty() &&
         mutual_gravity.empty() && pendulums.empty();
}

}  // namespace motus
