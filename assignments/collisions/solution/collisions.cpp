// The reference solution of the collisions assignment (for instructors: it scores full marks
// on every public and hidden test).
#include "collisions.hpp"

#include <cmath>
#include <limits>

namespace student {

void collide_balls(double m_a, VectorInOut v_a, double m_b, VectorInOut v_b, VectorIn n, double e) {
  const double closing = (v_b - v_a).dot(n);
  const double J = -(1 + e) * closing / (1 / m_a + 1 / m_b);
  v_a -= (J / m_a) * n;
  v_b += (J / m_b) * n;
}

void bounce_off_wall(VectorInOut v, VectorIn n, double e) { v -= (1 + e) * v.dot(n) * n; }

double time_of_impact(VectorIn p_a, VectorIn v_a, double r_a, VectorIn p_b, VectorIn v_b, double r_b) {
  const Vector dp = p_b - p_a, dv = v_b - v_a;
  const double R = r_a + r_b;
  // |dp + dv t|² = R²:  a t² + 2 b t + c = 0
  const double a = dv.dot(dv), b = dp.dot(dv), c = dp.dot(dp) - R * R;
  if (b >= 0) return std::numeric_limits<double>::infinity();  // not approaching
  if (c <= 0) return 0;                                          // touching already
  const double discriminant = b * b - a * c;
  if (discriminant < 0) return std::numeric_limits<double>::infinity();  // they pass each other
  return (-b - std::sqrt(discriminant)) / a;  // the first root: when they start to touch
}

double time_of_impact_with_plane(VectorIn p, VectorIn v, double r, VectorIn n, double offset) {
  const double gap = n.dot(p) - offset - r, closing = n.dot(v);
  if (closing >= 0) return std::numeric_limits<double>::infinity();
  if (gap <= 0) return 0;
  return gap / -closing;
}

}  // namespace student
