// A collisions plug-in with two of the assignment's common mistakes, for test_grade: the
// impulse over the sum of the masses (where the sum of the inverse masses belongs) and a wall
// bounce written for the floor alone. Its times of impact are right. motus must stop a run at
// the first wrong impulse or bounce, naming the function and the numbers.
#include <cmath>
#include <limits>

#include "motus/student/plugin.hpp"

namespace {

using student::VectorIn;
using student::VectorInOut;

void masses_summed(double m_a, VectorInOut v_a, double m_b, VectorInOut v_b, VectorIn n, double e) {
  const double J = -(1 + e) * (v_b - v_a).dot(n) / (m_a + m_b);
  v_a -= (J / m_a) * n;
  v_b += (J / m_b) * n;
}

void floor_only(VectorInOut v, VectorIn, double e) { v[1] = -e * v[1]; }

double time_of_impact(VectorIn p_a, VectorIn v_a, double r_a, VectorIn p_b, VectorIn v_b, double r_b) {
  const student::Vector dp = p_b - p_a, dv = v_b - v_a;
  const double R = r_a + r_b, a = dv.dot(dv), b = dp.dot(dv), c = dp.dot(dp) - R * R;
  if (b >= 0) return std::numeric_limits<double>::infinity();
  if (c <= 0) return 0;
  const double discriminant = b * b - a * c;
  if (discriminant < 0) return std::numeric_limits<double>::infinity();
  return (-b - std::sqrt(discriminant)) / a;
}

double time_of_impact_with_plane(VectorIn p, VectorIn v, double r, VectorIn n, double offset) {
  const double gap = n.dot(p) - offset - r, closing = n.dot(v);
  if (closing >= 0) return std::numeric_limits<double>::infinity();
  return gap <= 0 ? 0 : gap / -closing;
}

}  // namespace

MOTUS_PLUGIN("wrong", "collisions with two common mistakes (test_grade)") {
  plugin.collisions({masses_summed, floor_only, time_of_impact, time_of_impact_with_plane});
}
