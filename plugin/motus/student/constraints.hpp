#pragma once
// What a constraint projection works on (the cloth assignment): the bodies' positions and
// the sticks, pins and walls that hold them — Jakobsen's "Advanced Character Physics".
#include <vector>

#include "motus/student/student.hpp"

namespace student {

// Keeps bodies a and b at distance `length`.
struct Stick {
  int a = 0, b = 0;
  double length = 0;
};

// Holds `body` at `position`.
struct Pin {
  int body = 0;
  Vector position;
};

// A wall whose free side is normal·x ≥ offset (|normal| = 1): a body of radius r belongs
// where normal·x − offset ≥ r.
struct Wall {
  Vector normal;
  double offset = 0;
};

struct Constraints {
  std::vector<Stick> sticks;
  std::vector<Pin> pins;
  std::vector<Wall> walls;
  int iterations = 10;  // how many sweeps the scene asks for
};

// Every body's position (body i's coordinate k at x[i·d + k]), inverse mass 1/m and radius.
// A pinned body's inverse mass is its own 1/m too: weighing it as immovable (0) is yours to do.
struct Bodies {
  int dimensions;
  int count;
  VectorInOut x;
  Vector inverse_mass;
  Vector radius;

  // Body i's position, as d numbers you can read and change: bodies.position(i) += ...
  auto position(int i) { return x.segment(i * dimensions, dimensions); }
};

}  // namespace student
