// A collisions plug-in with a student's mistake from an audit, for test_grade: the time of impact
// of two balls takes the quadratic's later root (+√), the time they would part again after
// passing through each other. Its impulses and its times with planes are right.
#include <cmath>
#include <limits>

#include "right_collisions.hpp"

namespace {

using student::VectorIn;

double time_of_impact(VectorIn p_a, VectorIn v_a, double r_a, VectorIn p_b, VectorIn v_b, double r_b) {
  const student::Vector dp = p_b - p_a, dv = v_b - v_a;
  const double R = r_a + r_b, a = dv.dot(dv), b = dp.dot(dv), c = dp.dot(dp) - R * R;
  if (b >= 0) return std::numeric_limits<double>::infinity();
  if (c <= 0) return 0;
  const double discriminant = b * b - a * c;
  if (discriminant < 0) return std::numeric_limits<double>::infinity();
  return (-b + std::sqrt(discriminant)) / a;  // (the mistake: the later root)
}

}  // namespace

MOTUS_PLUGIN("later", "two balls' time of impact at the later root (test_grade)") {
  plugin.collisions({right::collide_balls, right::bounce_off_wall, time_of_impact, right::time_of_impact_with_plane});
}
