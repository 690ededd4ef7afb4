#pragma once
// The collision of two balls, "true elastic collisions" generalised to a coefficient of
// restitution e (docs/course.md, section 9; Wikipedia's elastic collision for unequal masses):
// along the contact normal n (from a to b), with closing speed u = (v_b − v_a)·n < 0,
// the impulse
//   J = −(1 + e) u / (1/m_a + 1/m_b)
//   v_a ← v_a − (J/m_a) n,   v_b ← v_b + (J/m_b) n
// keeps momentum exactly; e = 1 keeps kinetic energy too, and e < 1 removes exactly
//   ½ (1 − e²) u² / (1/m_a + 1/m_b).
// Tangential velocities are untouched (frictionless balls).
// The restitution of a pair is the product e_a · e_b (as in Bullet): a wall of e = 1
// lets the ball's own e count.
// A static wall is a body of infinite mass: v ← v − (1 + e)(v·n) n.
#include <Eigen/Core>

namespace motus {

template <class VecA, class VecB, class Normal>
void collide_balls(VecA&& v_a, VecB&& v_b, double inverse_mass_a, double inverse_mass_b, const Normal& n,
                   double e) {
  const double closing = (v_b - v_a).dot(n);
  if (closing >= 0) return;  // already separating
  const double J = -(1 + e) * closing / (inverse_mass_a + inverse_mass_b);
  v_a -= (J * inverse_mass_a) * n;
  v_b += (J * inverse_mass_b) * n;
}

template <class Vec, class Normal>
void bounce_off_wall(Vec&& v, const Normal& n, double e) {
  const double closing = v.dot(n);
  if (closing >= 0) return;
  v -= ((1 + e) * closing) * n;
}

}  // namespace motus
