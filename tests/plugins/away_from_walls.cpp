// A collisions plug-in whose time of impact with a plane has no "moving away: never" case, for
// test_grade: a ball that has just bounced off a wall touches it, moving away, and gets
// gap / −closing = 0 / (a negative number) = −0, a contact now; the bounce sends it back into
// the wall, and the contacts never end. Its impulses and its time of impact of two balls are right.
#include "right_collisions.hpp"

namespace {

double time_of_impact_with_plane(student::VectorIn p, student::VectorIn v, double r, student::VectorIn n, double offset) {
  const double gap = n.dot(p) - offset - r, closing = n.dot(v);  // (no "if (closing >= 0) return infinity;")
  return gap <= 0 ? 0 : gap / -closing;
}

}  // namespace

MOTUS_PLUGIN("away", "a time of impact with a plane for balls moving away too (test_grade)") {
  plugin.collisions({right::collide_balls, right::bounce_off_wall, right::time_of_impact, time_of_impact_with_plane});
}
