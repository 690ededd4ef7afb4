// A collisions plug-in whose time of impact with a plane has no "moving away: never" case, for
// test_grade: a ball that has just bounced off a wall touches it, moving away, and gets
// gap / −closing = 0 / (a negative number) = −0, a contact now; the bounce sends it back into
// the wall, and the contacts never end. Its impulses and its time of impact of two balls are right.
#include <cmath>
#include <limits>

#include "motus/student/plugin.hpp"

namespace {

using student::VectorIn;
using student::VectorInOut;

void collide(double m_a, VectorInOut v_a, double m_b, VectorInOut v_b, VectorIn n, double e) {
  const double J = -(1 + e) * (v_b - v_a).dot(n) / (1 / m_a + 1 / m_b);
  v_a -= (J / m_a) * n;
  v_b += (J / m_b) * n;
}

void bounce(VectorInOut v, VectorIn n, double e) { v -= (1 + e) * v.dot(n) * n; }

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
  const double gap = n.dot(p) - offset - r, closing = n.dot(v);  // (no "if (closing >= 0) return infinity;")
  return gap <= 0 ? 0 : gap / -closing;
}

}  // namespace

MOTUS_PLUGIN("away", "a time of impact with a plane for balls moving away too (test_grade)") {
  plugin.collisions({collide, bounce, time_of_impact, time_of_impact_with_plane});
}
