// A plug-in whose global's constructor throws as soon as it is opened (before motus asks it
// anything): test_grade's plug-in errors, one line naming it.
#include <stdexcept>

#include "motus/student/plugin.hpp"

namespace {

struct ThrowsWhenBuilt {
  ThrowsWhenBuilt() { throw std::runtime_error("thrown on purpose while loading"); }
};
const ThrowsWhenBuilt kGlobal;

void euler(const student::FirstOrderSystem&, double, double, student::VectorInOut) {}

}  // namespace

MOTUS_PLUGIN("loads_badly", "a global that throws when the library is opened (test_grade)") {
  plugin.first_order("euler", 1, "never reached", euler);
}
