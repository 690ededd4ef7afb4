#pragma once
// Verlet constraints, as in Jakobsen's "Advanced Character Physics" and the course's
// fabric-and-ragdoll demo (docs/course.md, section 10): sticks keep two bodies at a fixed distance, pins hold a body
// at a fixed point.
#include <array>

namespace motus {

struct StickConstraint {
  int a = 0, b = 1;
  double length = 0;  // rest length, m
};

struct PinConstraint {
  int body = 0;
  std::array<double, 3> position{0, 0, 0};
};

}  // namespace motus
