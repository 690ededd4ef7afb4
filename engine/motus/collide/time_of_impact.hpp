#pragma once
// When do two bodies moving on straight lines first touch? ("continuous collision":
// however fast they move, the contact is found at its time, never skipped over.)
#include <cmath>
#include <limits>

namespace motus {

constexpr double kNoImpact = std::numeric_limits<double>::infinity();

// Two spheres: relative position dp = p_b − p_a, relative velocity dv = v_b − v_a,
// touching at distance R = r_a + r_b. Solve |dp + dv t|² = R² for the first t in
// [0, horizon] while approaching:
//   a t² + 2 b t + c = 0,  a = dv·dv,  b = dp·dv,  c = dp·dp − R²
//   t = (−b − √(b² − ac)) / a  =  c / (−b + √(b² − ac))   (the second form keeps digits)
// Already touching or overlapping (c ≤ 0) and approaching (b < 0): t = 0.
inline double sphere_sphere_impact(double dp_dp, double dp_dv, double dv_dv, double R, double horizon) {
  if (dp_dv >= 0) return kNoImpact;  // not approaching
  const double c = dp_dp - R * R;
  if (c <= 0) return 0;
  // Most pairs are decided without a square root: if they are still closing at the
  // horizon, their distance falls all the way, so being apart then means apart
  // throughout.
  if (dp_dv + dv_dv * horizon <= 0 && c + horizon * (2 * dp_dv + dv_dv * horizon) > 0) return kNoImpact;
  const double discriminant = dp_dv * dp_dv - dv_dv * c;
  if (discriminant < 0) return kNoImpact;  // they pass each other
  const double t = c / (-dp_dv + std::sqrt(discriminant));
  return t <= horizon ? t : kNoImpact;
}

// A sphere and a plane: `gap` = n·p − offset − r (the distance left to touch), `closing`
// = n·v (negative when moving towards the plane). Linear: t = gap / −closing.
inline double sphere_plane_impact(double gap, double closing, double horizon) {
  if (closing >= 0) return kNoImpact;
  if (gap <= 0) return 0;
  const double t = gap / -closing;
  return t <= horizon ? t : kNoImpact;
}

}  // namespace motus
