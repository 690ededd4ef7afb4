// A constraint projection that answers NaN: every body's position, at its first call (test_grade:
// a run's stick and pin errors must then read as not finite, never as the last finite ones).
#include <limits>

#include "motus/student/plugin.hpp"

namespace {

void satisfy_constraints(student::Bodies& bodies, const student::Constraints&) {
  bodies.x.setConstant(std::numeric_limits<double>::quiet_NaN());
}

}  // namespace

MOTUS_PLUGIN("nan", "a constraint projection that answers NaN (test_grade)") { plugin.constraints(satisfy_constraints); }
