// The collisions assignment as a motus plug-in: your functions (collisions.cpp) take the place
// of motus's own impulses and times of impact in every run that loads it. This file is the
// assignment's; the grader uses its own copy, so there is nothing to change here.
#include "collisions.hpp"
#include "motus/student/plugin.hpp"

MOTUS_PLUGIN("student", "the collisions assignment (collisions.cpp)") {
  plugin.collisions({student::collide_balls, student::bounce_off_wall, student::time_of_impact,
                     student::time_of_impact_with_plane});
}
