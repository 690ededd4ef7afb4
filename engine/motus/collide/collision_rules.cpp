// The impulses and times of impact of a contact: the engine's own (impulse.hpp, time_of_impact.hpp), or
// a plug-in's (a student's collision rules), checked against what any correct one must give, so that a
// mistake is named where it is made rather than found later as contacts that never end.
#include "motus/collide/ball_collisions.hpp"

#include <cmath>
#include <string>

#include "motus/collide/ball_collisions_tuning.hpp"
#include "motus/collide/impulse.hpp"
#include "motus/collide/time_of_impact.hpp"
#include "motus/message_number.hpp"

namespace motus {

using namespace ball_collisions_tuning;

namespace {
// A number in a message to a plug-in's author: six significant figures.
std::string figure(double x) { return message_number(x, 6); }
}  // namespace

template <int D>
double BallCollisions<D>::outside_balls_impact(const Point& p_a, const Point& v_a, double r_a, const Point& p_b,
                                               const Point& v_b, double r_b, double horizon) {
  double t = kNoImpact;
  check_external(rules_->balls_impact(rules_->self, D, p_a.data(), v_a.data(), r_a, p_b.data(), v_b.data(), r_b, &t),
                 "time of impact of two balls", rules_->error, rules_->self);
  if (std::isnan(t)) throw ExternalError("returned NaN as the time of impact of two balls (a time ≥ 0, or +infinity for none)");
  // A time before now is taken as "none" (as −1 for none is, a common way to write it). But
  // for balls that already touch and approach it loses a contact that is happening now, and they
  // pass into each other: that showed only much later, as an overlap. So does a later time.
  // (Touching to within rounding: a contact leaves its balls exactly touching, and their
  // neighbours in a chain too.)
  const Point dp = p_b - p_a, dv = v_b - v_a;
  const double R = r_a + r_b, slack = kAtContact * R + kPositionRounding * (p_a.norm() + p_b.norm());
  const double distance = dp.norm(), gap = distance - R, opening = dp.dot(dv);  // opening < 0: approaching
  if (gap <= kTouching * R && opening < 0 && (t < 0 || (t <= horizon && t * (-opening / distance) > slack)))
    throw ExternalError("returned " + figure(t) + " as the time of impact of two balls whose surfaces are " +
                        figure(gap) + " m apart and approaching, where they already touch" +
                        (gap < 0 ? " (overlap)" : "") + ": that is a contact now, t = 0");
  // And a contact within the step for balls clearly moving apart (beyond rounding) is none: it
  // would have the impulse pull them together. (The impulse's own check looks only at balls that
  // approach; without this the contacts went on until the step's limit.)
  if (t >= 0 && t <= horizon && opening > kTouching * distance * dv.norm())
    throw ExternalError("returned " + figure(t) + " as the time of impact of two balls moving apart (the gap between "
                        "their surfaces grows at " + figure(opening / distance) +
                        " m/s): balls moving apart never touch, +infinity");
  // A time within the step must be one at which they touch, approaching (the later root, where
  // they would part again having passed through each other, is not), and balls that clearly meet
  // within the step have one. Without this the run went on with them inside each other, and it
  // showed only as overlaps.
  if (!(t >= 0 && t <= horizon) && gap > kTouching * R && opening < 0) {
    // They clearly meet within the step when the quadratic's earlier root is in it (a grazing pass,
    // whose two roots are as one, is left to the plug-in's rounding).
    const double a = dv.dot(dv), c = (distance - R) * (distance + R), discriminant = opening * opening - a * c;
    if (discriminant > kAtContact * opening * opening &&
        c / (-opening + std::sqrt(discriminant)) < horizon * (1 - kAtContact))
      throw ExternalError("returned " + (t > horizon ? figure(t) : std::string("none")) +
                          " as the time of impact of two balls whose surfaces are " + figure(gap) +
                          " m apart and approaching: they meet within the " + figure(horizon) + " s left of the step");
  }
  if (t >= 0 && t <= horizon && gap > kTouching * R) {
    const Point apart_then = dp + t * dv;
    const double gap_then = apart_then.norm() - R;
    if (std::abs(gap_then) > slack)
      throw ExternalError("returned " + figure(t) + " as the time of impact of two balls whose surfaces are " +
                          figure(gap) + " m apart: then they would be " + figure(std::abs(gap_then)) +
                          (gap_then < 0 ? " m into each other" : " m apart") +
                          ", not touching (they touch where |p_b + t v_b - p_a - t v_a| = r_a + r_b)");
    if (apart_then.dot(dv) > kAtContact * R * dv.norm())
      throw ExternalError("returned " + figure(t) + " as the time of impact of two balls whose surfaces are " +
                          figure(gap) + " m apart: then they touch moving apart, having passed through each " +
                          "other (the later root); they meet at the earlier one");
  }
  return t >= 0 && t <= horizon ? t : kNoImpact;  // (negative: none, as +infinity)
}

template <int D>
double BallCollisions<D>::outside_plane_impact(const Point& p, const Point& v, double r, const Plane& plane,
                                               double horizon) {
  double t = kNoImpact;
  check_external(rules_->plane_impact(rules_->self, D, p.data(), v.data(), r, plane.normal.data(), plane.offset, &t),
                 "time of impact of a ball and a plane", rules_->error, rules_->self);
  if (std::isnan(t))
    throw ExternalError("returned NaN as the time of impact of a ball and a plane (a time ≥ 0, or +infinity for none)");
  // (As for two balls: a ball that already touches the plane and moves into it has a contact now,
  // not before, not later.)
  const double gap = plane.normal.dot(p) - plane.offset - r, away = plane.normal.dot(v);  // away < 0: into it
  const double slack = kAtContact * r + kPositionRounding * (std::abs(plane.normal.dot(p)) + std::abs(plane.offset));
  const bool touching = gap <= kTouching * std::max(r, 1e-300);
  if (touching && away < 0 && (t < 0 || (t <= horizon && t * -away > slack)))
    throw ExternalError("returned " + figure(t) + " as the time of impact of a ball " + figure(gap) +
                        " m from a plane and moving into it, where it already touches" +
                        (gap < 0 ? " (it is into the plane)" : "") + ": that is a contact now, t = 0");
  if (t >= 0 && t <= horizon && away > kTouching * v.norm())
    throw ExternalError("returned " + figure(t) + " as the time of impact of a ball moving away from a plane (at " +
                        figure(away) + " m/s along its normal): it never reaches it, +infinity");
  // As for two balls: a time within the step is one at which the ball touches the plane, and a ball
  // that clearly reaches it within the step has a time in it (the radius left out of the gap gave
  // the time its centre reaches the plane: beyond the step, or with the ball r deep in the plane).
  if (!(t >= 0 && t <= horizon) && !touching && gap + away * horizon < -slack)
    throw ExternalError("returned " + (t > horizon ? figure(t) : std::string("none")) + " as the time of impact of a ball " +
                        figure(gap) + " m from a plane and moving into it at " + figure(-away) +
                        " m/s: it reaches the plane within the " + figure(horizon) + " s left of the step");
  if (const double gap_then = gap + away * t; t >= 0 && t <= horizon && !touching && std::abs(gap_then) > slack)
    throw ExternalError("returned " + figure(t) + " as the time of impact of a ball " + figure(gap) +
                        " m from a plane: then it would be " + figure(std::abs(gap_then)) +
                        (gap_then < 0 ? " m into the plane" : " m from it") +
                        ", not touching it (the gap between them is n.p - offset - r)");
  return t >= 0 && t <= horizon ? t : kNoImpact;
}

template <int D>
void BallCollisions<D>::collide(int i, int k, const Point& n, double e) {
  if (!rules_) {
    collide_balls(velocity(i), velocity(k), inverse_mass_of(i), inverse_mass_of(k), n, e);
    return;
  }
  const double closing = (velocity(k) - velocity(i)).dot(n);  // u, < 0: approaching
  const double scale = velocity(i).norm() + velocity(k).norm();
  check_external(rules_->collide_balls(rules_->self, D, v_ + D * i, v_ + D * k, 1 / inverse_mass_of(i),
                                       1 / inverse_mass_of(k), n.data(), e),
                 "impulse between two balls", rules_->error, rules_->self);
  // What any impulse along n must leave (Newton's law of restitution): the balls separating at
  // u' = −e u. A plug-in's that does not — the masses summed, no (1 + e), the normal's sign — would
  // otherwise show only much later, as contacts that never end or velocities that overflow, and be
  // read as a time of impact's mistake. (Only for balls that approach: a plug-in's time of impact
  // may have found a contact between balls moving apart, and that is its own mistake.)
  const double after = (velocity(k) - velocity(i)).dot(n);
  if (!std::isfinite(after))
    throw ExternalError("the impulse between two balls returned velocities that are not finite (from finite ones)");
  if (closing < 0 && !(std::abs(after + e * closing) <= 1e-9 * scale))
    throw ExternalError("the impulse between balls " + std::to_string(i) + " and " + std::to_string(k) + " left them " +
                        (after < 0 ? "approaching" : "separating") + " at " + figure(after) +
                        " m/s along the normal, where restitution e = " + figure(e) +
                        " asks them to separate at -e u = " + figure(-e * closing) + " m/s (they met at u = " +
                        figure(closing) + " m/s): check (1 + e), the inverse masses and the normal's direction");
}

template <int D>
void BallCollisions<D>::bounce(int i, const Point& n, double e) {
  if (!rules_) {
    bounce_off_wall(velocity(i), n, e);
    return;
  }
  const double into = velocity(i).dot(n);  // < 0: moving into the wall
  const double scale = velocity(i).norm();
  check_external(rules_->bounce_off_wall(rules_->self, D, v_ + D * i, n.data(), e), "bounce off a wall",
                 rules_->error, rules_->self);
  // The same law against a wall: n·v' = −e n·v (see collide).
  const double after = velocity(i).dot(n);
  if (!std::isfinite(after))
    throw ExternalError("the bounce off a wall returned a velocity that is not finite (from a finite one)");
  if (into < 0 && !(std::abs(after + e * into) <= 1e-9 * scale)) {
    std::string normal;
    for (int k = 0; k < D; ++k) {
      if (k) normal += ", ";
      normal += figure(n[k] + 0.0);  // (+ 0.0: a box face's −0 reads as 0)
    }
    throw ExternalError("the bounce off a wall left ball " + std::to_string(i) + " with n.v = " + figure(after) +
                        " m/s, where restitution e = " + figure(e) + " asks -e n.v = " + figure(-e * into) +
                        " m/s (it met the wall, normal (" + normal + "), at n.v = " + figure(into) +
                        " m/s): only the part of v along the wall's normal changes");
  }
}

// This file's members, for each dimension the class is instantiated for (ball_collisions.cpp).
#define MOTUS_COLLISION_RULES(D) \
  template double BallCollisions<D>::outside_balls_impact(const typename BallCollisions<D>::Point&, const typename BallCollisions<D>::Point&, double, const typename BallCollisions<D>::Point&, const typename BallCollisions<D>::Point&, double, double); \
  template double BallCollisions<D>::outside_plane_impact(const typename BallCollisions<D>::Point&, const typename BallCollisions<D>::Point&, double, const typename BallCollisions<D>::Plane&, double); \
  template void BallCollisions<D>::collide(int, int, const typename BallCollisions<D>::Point&, double); \
  template void BallCollisions<D>::bounce(int, const typename BallCollisions<D>::Point&, double);
MOTUS_COLLISION_RULES(1)
MOTUS_COLLISION_RULES(2)
MOTUS_COLLISION_RULES(3)
#undef MOTUS_COLLISION_RULES

}  // namespace motus
