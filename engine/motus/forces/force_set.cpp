#include "motus/forces/force_set.hpp"

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

bool ForceSet::empty() const {
  return gravity.empty() && springs.empty() && drag.empty() && central_gravity.empty() &&
         mutual_gravity.empty() && pendulums.empty();
}

}  // namespace motus
