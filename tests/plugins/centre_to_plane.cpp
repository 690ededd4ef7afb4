// A collisions plug-in with a student's mistake from an audit, for test_grade: the time of impact
// with a plane leaves the radius out of the gap (n·p − offset, the centre's distance), so it gives
// the time the ball's centre reaches the plane, with the ball r deep in it. Its impulses and its
// times for two balls are right.
#include <cmath>
#include <limits>

#include "right_collisions.hpp"

namespace {

using student::VectorIn;

double time_of_impact_with_plane(VectorIn p, VectorIn v, double r, VectorIn n, double offset) {
  (void)r;  // (the mistake)
  const double gap = n.dot(p) - offset, closing = n.dot(v);
  if (closing >= 0) return std::numeric_limits<double>::infinity();
  return gap <= 0 ? 0 : gap / -closing;
}

}  // namespace

MOTUS_PLUGIN("centre", "a plane's time of impact with the radius left out (test_grade)") {
  plugin.collisions({right::collide_balls, right::bounce_off_wall, right::time_of_impact, time_of_impact_with_plane});
}
