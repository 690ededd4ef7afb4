// The reference solution of the cloth assignment (for instructors: it scores full marks on
// every public and hidden test).
#include "cloth.hpp"

namespace student {

void project_stick(VectorInOut x_a, VectorInOut x_b, double w_a, double w_b, double length) {
  const double w = w_a + w_b;
  if (w == 0) return;  // both ends held
  const Vector delta = x_b - x_a;
  const double current = delta.norm();
  if (current == 0) return;  // no direction to push along
  const double stretch = (current - length) / (current * w);
  x_a += (stretch * w_a) * delta;
  x_b -= (stretch * w_b) * delta;
}

void project_wall(VectorInOut x, double r, const Wall& wall) {
  const double height = wall.normal.dot(x) - wall.offset - r;
  if (height < 0) x -= height * wall.normal;
}

void satisfy_constraints(Bodies& bodies, const Constraints& c) {
  Vector w = bodies.inverse_mass;
  for (const auto& p : c.pins) w[p.body] = 0;  // a pinned body is infinitely heavy
  // On their pins first, so the sticks pull towards where the pins really are; and last, exactly.
  for (const auto& p : c.pins) bodies.position(p.body) = p.position;
  for (int sweep = 0; sweep < c.iterations; ++sweep) {
    for (const auto& s : c.sticks) project_stick(bodies.position(s.a), bodies.position(s.b), w[s.a], w[s.b], s.length);
    for (int i = 0; i < bodies.count; ++i)
      if (w[i] > 0)
        for (const auto& wall : c.walls) project_wall(bodies.position(i), bodies.radius[i], wall);
  }
  for (const auto& p : c.pins) bodies.position(p.body) = p.position;
}

}  // namespace student
