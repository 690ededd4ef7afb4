// Balls against walls: planes, the faces of box containers and (2-D) segments — their times of impact,
// their normals, and a ball moved out of a wall it is in.
#include "motus/collide/ball_collisions.hpp"

#include <algorithm>
#include <cmath>

#include "motus/collide/ball_collisions_tuning.hpp"
#include "motus/collide/time_of_impact.hpp"

namespace motus {

using namespace ball_collisions_tuning;

template <int D>
void BallCollisions<D>::initial_plane_event(int i, int w) {
  const Plane& plane = planes_[static_cast<size_t>(w)];
  auto p = position(i);
  const auto u = velocity(i);
  double gap = plane_gap(plane, p, radius_of(i));
  if (gap < 0) {  // rounding (or the scene) left it a hair inside the wall
    p -= gap * plane.normal;
    moved_apart(i, -gap);
    gap = 0;
    ++counters_.position_corrections;
  }
  const double closing = plane_closing(plane, u);
  if (gap + closing * h_ > 0) return;  // does not reach it this step
  const double toi = rules_ ? outside_plane_impact(p, u, radius_of(i), plane, h_) : sphere_plane_impact(gap, closing, h_, radius_of(i));
  if (toi != kNoImpact) push(toi, i, -1 - w);
}

template <int D>
void BallCollisions<D>::find_wall_events(int i, double t) {
  const Point p = position_at(i, t);
  const Point u = velocity(i);
  const double r = radius_of(i), horizon = h_ - t;
  double first = horizon;  // (the first contact found, from t)
  for (size_t w = 0; w < planes_.size(); ++w) {
    const Plane& plane = planes_[w];
    const double gap = plane_gap(plane, p, r), closing = plane_closing(plane, u);
    const double toi = rules_ ? outside_plane_impact(p, u, r, plane, horizon) : sphere_plane_impact(gap, closing, horizon, r);
    if (toi != kNoImpact) push(t + toi, i, -1 - static_cast<int>(w)), first = std::min(first, toi);
  }
  for (size_t s = 0; s < segments_.size(); ++s) {
    const double toi = segment_impact(segments_[s], p, u, r, horizon, nullptr);
    if (toi != kNoImpact) push(t + toi, i, -1 - static_cast<int>(planes_.size() + s)), first = std::min(first, toi);
  }
  // (The event's own time: a contact of its at exactly that time may still come first, by the
  // bodies' numbers.)
  state_[i].horizon = first < horizon ? t + first : h_;
}

template <int D>
double BallCollisions<D>::segment_impact(const Segment& s, const Point& p, const Point& u, double r, double horizon,
                                         Point* normal) const {
  if constexpr (D == 2) {
    // For the ball's centre a segment is a capsule of radius r: two flat sides and two
    // round ends. The first of those it reaches is the contact.
    const Point along = s.b - s.a;
    const double length = along.norm();
    const Point tangent = along / length;
    const Point side(-tangent[1], tangent[0]);
    double best = kNoImpact;
    Point best_normal = side;
    const double offset = side.dot(p - s.a);
    const double sign = offset > 0 || (offset == 0 && side.dot(u) < 0) ? 1 : -1;
    const double toi = sphere_plane_impact(sign * offset - r, sign * side.dot(u), horizon, r);
    if (toi != kNoImpact) {
      const double reach = tangent.dot(p + u * toi - s.a);
      if (reach >= 0 && reach <= length) {
        best = toi;
        best_normal = sign * side;
      }
    }
    for (const Point* end : {&s.a, &s.b}) {
      const Point d = p - *end;
      const double te = far_apart(d.squaredNorm(), r) ? far_sphere_sphere_impact(d, u, r, horizon)
                                                      : sphere_sphere_impact(d.squaredNorm(), d.dot(u), u.squaredNorm(), r, horizon);
      if (te < best) {
        best = te;
        best_normal = (p + u * te - *end).normalized();
      }
    }
    if (normal) *normal = best_normal;
    return best;
  } else {
    (void)s, (void)p, (void)u, (void)r, (void)horizon, (void)normal;
    return kNoImpact;
  }
}

template <int D>
typename BallCollisions<D>::Point BallCollisions<D>::nearest_on(const Segment& s, const Point& p) {
  const Point along = s.b - s.a;
  const double reach = std::clamp(along.dot(p - s.a) / along.squaredNorm(), 0.0, 1.0);
  return s.a + reach * along;
}

template <int D>
typename BallCollisions<D>::Point BallCollisions<D>::wall_normal(int i, int wall) {
  if (wall < static_cast<int>(planes_.size())) return planes_[static_cast<size_t>(wall)].normal;
  // A segment, at the moment of contact: the normal points from the nearest point of the
  // segment — on a flat side or a round end — to the ball's centre. (Found from the geometry,
  // not by searching for an impact again: at the contact itself rounding can put the ball a
  // hair short of the end cap, and the search would then fall back to the flat side.)
  const Segment& s = segments_[static_cast<size_t>(wall) - planes_.size()];
  const Point away = position(i) - nearest_on(s, position(i));
  const double distance = away.norm();
  if (distance > 0) return away / distance;
  Point side = Point::Zero();  // on the segment itself: the side it comes from
  if constexpr (D == 2) {
    const Point along = s.b - s.a;
    side = Point(-along[1], along[0]).normalized();
    if (side.dot(velocity(i)) > 0) side = -side;
  }
  return side;
}

template <int D>
void BallCollisions<D>::separate_from_walls(int i) {
  // (rounding can leave a body a hair inside a wall)
  for (int w = 0; w < static_cast<int>(planes_.size()); ++w)
    if (const double moved = push_out_of_plane(i, w); moved > 0) moved_apart(i, moved);
  if constexpr (D == 2) {
    for (const Segment& s : segments_)
      if (const double moved = push_off_segment(i, s); moved > 0) moved_apart(i, moved);
  }
}

template <int D>
double BallCollisions<D>::push_out_of_plane(int i, int wall) {
  const Plane& plane = planes_[static_cast<size_t>(wall)];
  const double gap = plane_gap(plane, position(i), radius_of(i));
  if (!(gap < 0)) return 0;
  position(i) -= gap * plane.normal;
  ++counters_.position_corrections;
  return -gap;
}

template <int D>
double BallCollisions<D>::push_off_segment(int i, const Segment& s) {
  const Point d = position(i) - nearest_on(s, position(i));
  const double distance = d.norm();
  if (!(distance < radius_of(i))) return 0;
  if (distance > 0) {
    position(i) += (radius_of(i) - distance) / distance * d;
  } else if constexpr (D == 2) {
    // Its centre on the segment: no side to push it out to, so the one its normal points to,
    // (−(b − a)_y, (b − a)_x) (a ball set on a segment stayed in it, whole, step after step).
    const Point along = s.b - s.a;
    Point normal = Point::UnitX();
    if (const double length = along.norm(); length > 0) normal << -along[1] / length, along[0] / length;
    position(i) += radius_of(i) * normal;
  }
  ++counters_.position_corrections;
  return radius_of(i) - distance;
}

// This file's members, for each dimension the class is instantiated for (ball_collisions.cpp).
#define MOTUS_WALL_CONTACTS(D) \
  template void BallCollisions<D>::initial_plane_event(int, int); \
  template void BallCollisions<D>::find_wall_events(int, double); \
  template double BallCollisions<D>::segment_impact(const typename BallCollisions<D>::Segment&, const typename BallCollisions<D>::Point&, const typename BallCollisions<D>::Point&, double, double, typename BallCollisions<D>::Point*) const; \
  template typename BallCollisions<D>::Point BallCollisions<D>::nearest_on(const typename BallCollisions<D>::Segment&, const typename BallCollisions<D>::Point&); \
  template typename BallCollisions<D>::Point BallCollisions<D>::wall_normal(int, int); \
  template void BallCollisions<D>::separate_from_walls(int); \
  template double BallCollisions<D>::push_out_of_plane(int, int); \
  template double BallCollisions<D>::push_off_segment(int, const typename BallCollisions<D>::Segment&);
MOTUS_WALL_CONTACTS(1)
MOTUS_WALL_CONTACTS(2)
MOTUS_WALL_CONTACTS(3)
#undef MOTUS_WALL_CONTACTS

}  // namespace motus
