// A collisions plug-in with two of the assignment's common mistakes, for test_grade: the
// impulse over the sum of the masses (where the sum of the inverse masses belongs) and a wall
// bounce written for the floor alone. Its times of impact are right. motus must stop a run at
// the first wrong impulse or bounce, naming the function and the numbers.
#include "right_collisions.hpp"

namespace {

using student::VectorIn;
using student::VectorInOut;

void masses_summed(double m_a, VectorInOut v_a, double m_b, VectorInOut v_b, VectorIn n, double e) {
  const double J = -(1 + e) * (v_b - v_a).dot(n) / (m_a + m_b);
  v_a -= (J / m_a) * n;
  v_b += (J / m_b) * n;
}

void floor_only(VectorInOut v, VectorIn, double e) { v[1] = -e * v[1]; }

}  // namespace

MOTUS_PLUGIN("wrong", "collisions with two common mistakes (test_grade)") {
  plugin.collisions({masses_summed, floor_only, right::time_of_impact, right::time_of_impact_with_plane});
}
