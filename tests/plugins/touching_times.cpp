// A collisions plug-in with the assignment's commonest time-of-impact mistake, for test_grade:
// no "already touching and approaching → 0" case. Balls left touching by a contact (Newton's
// cradle's, or a ball that has come to rest on the floor) then get the quadratic's root for a
// gap of a rounding's size below zero: a time just before now, which motus once took as "no
// contact", letting them pass into each other. Its impulses are right.
#include <cmath>
#include <limits>

#include "right_collisions.hpp"

namespace {

using student::VectorIn;

double time_of_impact(VectorIn p_a, VectorIn v_a, double r_a, VectorIn p_b, VectorIn v_b, double r_b) {
  const student::Vector dp = p_b - p_a, dv = v_b - v_a;
  const double R = r_a + r_b, a = dv.dot(dv), b = dp.dot(dv), c = dp.dot(dp) - R * R;
  if (b >= 0) return std::numeric_limits<double>::infinity();
  const double discriminant = b * b - a * c;  // (no "if (c <= 0) return 0;")
  if (discriminant < 0) return std::numeric_limits<double>::infinity();
  return (-b - std::sqrt(discriminant)) / a;
}

double time_of_impact_with_plane(VectorIn p, VectorIn v, double r, VectorIn n, double offset) {
  const double gap = n.dot(p) - offset - r, closing = n.dot(v);
  if (closing >= 0) return std::numeric_limits<double>::infinity();
  return gap / -closing;  // (no "gap <= 0 ? 0 :")
}

}  // namespace

MOTUS_PLUGIN("touching", "times of impact without the already-touching case (test_grade)") {
  plugin.collisions({right::collide_balls, right::bounce_off_wall, time_of_impact, time_of_impact_with_plane});
}
