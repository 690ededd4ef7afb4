#pragma once
// The collisions assignment's four functions done right (as its solution does them), for the
// test plug-ins that each get one of them wrong on purpose and take the other three from here.
#include <cmath>
#include <limits>

#include "motus/student/plugin.hpp"

namespace right {

using student::VectorIn;
using student::VectorInOut;

inline void collide_balls(double m_a, VectorInOut v_a, double m_b, VectorInOut v_b, VectorIn n, double e) {
  const double J = -(1 + e) * (v_b - v_a).dot(n) / (1 / m_a + 1 / m_b);
  v_a -= (J / m_a) * n;
  v_b += (J / m_b) * n;
}

inline void bounce_off_wall(VectorInOut v, VectorIn n, double e) { v -= (1 + e) * v.dot(n) * n; }

inline double time_of_impact(VectorIn p_a, VectorIn v_a, double r_a, VectorIn p_b, VectorIn v_b, double r_b) {
  const student::Vector dp = p_b - p_a, dv = v_b - v_a;
  const double R = r_a + r_b, a = dv.dot(dv), b = dp.dot(dv), c = dp.dot(dp) - R * R;
  if (b >= 0) return std::numeric_limits<double>::infinity();
  if (c <= 0) return 0;
  const double discriminant = b * b - a * c;
  if (discriminant < 0) return std::numeric_limits<double>::infinity();
  return (-b - std::sqrt(discriminant)) / a;
}

inline double time_of_impact_with_plane(VectorIn p, VectorIn v, double r, VectorIn n, double offset) {
  const double gap = n.dot(p) - offset - r, closing = n.dot(v);
  if (closing >= 0) return std::numeric_limits<double>::infinity();
  return gap <= 0 ? 0 : gap / -closing;
}

}  // namespace right
