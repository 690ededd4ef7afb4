// A plug-in whose integrators misbehave on purpose, for test_grade's plug-in errors:
// "bad:throws" throws, "bad:crashes" dereferences a null pointer.
#include <stdexcept>

#include "motus/student/plugin.hpp"

namespace {

void throws(const student::FirstOrderSystem&, double, double, student::VectorInOut) {
  throw std::runtime_error("thrown on purpose");
}

void crashes(const student::FirstOrderSystem&, double, double, student::VectorInOut y) {
  *static_cast<volatile double*>(nullptr) = y[0];
}

}  // namespace

MOTUS_PLUGIN("bad", "integrators that misbehave (test_grade)") {
  plugin.first_order("throws", 1, "throws std::runtime_error", throws);
  plugin.first_order("crashes", 1, "dereferences a null pointer", crashes);
}
