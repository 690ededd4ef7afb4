#pragma once
// When do two bodies moving on straight lines first touch? ("continuous collision":
// however fast they move, the contact is found at its time, never skipped over.)
#include <algorithm>
#include <cmath>
#include <limits>

namespace motus {

constexpr double kNoImpact = std::numeric_limits<double>::infinity();

// Two spheres: relative position dp = p_b − p_a, relative velocity dv = v_b − v_a,
// touching at distance R = r_a + r_b. Solve |dp + dv t|² = R² for the first t in
// [0, horizon] while approaching:
//   a t² + 2 b t + c = 0,  a = dv·dv,  b = dp·dv,  c = dp·dp − R²
//   t = (−b − √(b² − ac)) / a  =  c / (−b + √(b² − ac))   (the second form keeps digits)
// Already touching or overlapping (c ≤ 0) and approaching (b < 0): t = 0 — unless they approach
// so slowly that by the horizon they close less than kRoundingOverlap of R, which is rounding,
// not a contact (the pair pass takes no overlap that small for one). Without that, a stack of
// balls at rest with little restitution took contact after contact at one instant, each one
// halving the last one's speed, down to the smallest double (inelastic collapse: over a thousand
// contacts in a step for two balls on a floor, and the run failed).
constexpr double kRoundingOverlap = 1e-12;
inline double sphere_sphere_impact(double dp_dp, double dp_dv, double dv_dv, double R, double horizon) {
  if (dp_dv >= 0) return kNoImpact;  // not approaching
  const double c = dp_dp - R * R;
  // (−b/R is the closing speed, −b·horizon/R at most the distance closed by the horizon; and
  // c + horizon (2b + a horizon) is the squared distance then, less R².)
  if (-dp_dv * horizon <= 0.5 * kRoundingOverlap * R * R &&
      c + horizon * (2 * dp_dv + dv_dv * horizon) > -kRoundingOverlap * R * R)
    return kNoImpact;
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

// The same for two spheres far apart for their size. c and b² − ac above are differences of
// numbers of size d², d = |dp|, and lose R's digits as d/R grows: the contact's position is off
// by about ε d²/R (ε = 2.2e-16), and from d ≈ 1e8 R on, R is lost altogether and the spheres
// pass through each other (a ball of 0.1 m at 1e10 m/s, 1e9 radii a step). From 1e4 R on
// (an error of 1e-8 R before) the closest approach is found first, t_c = −b/a, where the miss
// vector m = dp + dv t_c is computed as a vector, with no such loss, and the contact from it:
//   t = t_c − √((R² − m·m) / a).
// (The callers test far_apart first and call the scalar form above otherwise: the pair pass and
// the contacts' searches stay as they were.)
constexpr double kFarApart2 = 1e8;  // (d/R)² from which the closest approach is found first
inline bool far_apart(double dp_dp, double R) { return dp_dp > kFarApart2 * R * R; }

template <class Vec>
double far_sphere_sphere_impact(const Vec& dp, const Vec& dv, double R, double horizon) {
  const double dp_dv = dp.dot(dv), dv_dv = dv.squaredNorm();
  if (dp_dv >= 0) return kNoImpact;  // not approaching
  const double closest = -dp_dv / dv_dv;
  const double miss2 = (dp + dv * closest).squaredNorm();
  if (!(miss2 < R * R)) return kNoImpact;  // they pass each other
  const double t = closest - std::sqrt((R * R - miss2) / dv_dv);
  return t <= horizon ? std::max(t, 0.0) : kNoImpact;
}

// A sphere of radius r and a plane: `gap` = n·p − offset − r (the distance left to touch),
// `closing` = n·v (negative when moving towards the plane). Linear: t = gap / −closing.
// Touching and moving in so slowly that by the horizon it has gone less than kRoundingOverlap of
// r into the plane is rounding, as for two spheres (a cluster of balls settled at once on a floor,
// contact_cluster.hpp, is left at rest to within rounding, and found its contact again and again).
inline double sphere_plane_impact(double gap, double closing, double horizon, double r) {
  if (closing >= 0) return kNoImpact;
  if (-closing * horizon <= 0.5 * kRoundingOverlap * r && gap + closing * horizon > -kRoundingOverlap * r)
    return kNoImpact;
  if (gap <= 0) return 0;
  const double t = gap / -closing;
  return t <= horizon ? t : kNoImpact;
}

}  // namespace motus
