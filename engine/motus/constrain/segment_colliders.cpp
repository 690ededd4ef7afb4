// Segment colliders (2-D): the pass of every free body against every segment, and the side of each
// segment each body was last seen on. Its own part: a collider with a memory of its own, in 2-D only.
#include "motus/constrain/constraint_projection.hpp"

#include <algorithm>
#include <cstddef>

namespace motus {

// Every free body against every segment (2-D).
void ConstraintProjection::project_segments(VectorRef x) const {
  if (colliders_.segments.empty()) return;
  const int n = static_cast<int>(radius_.size());
  for (int i = 0; i < n; ++i) {
    if (inverse_mass_[i] == 0) continue;
    auto xi = x.segment(i * d_, d_);
    for (size_t j = 0; j < colliders_.segments.size(); ++j) project_segment(j, i, xi);
  }
}

// A 2-D segment has two sides and no inside. A ball closer than its radius to the segment
// is pushed away from the nearest point. A point (or a ball fast enough to pass through in
// one step) could end up on the other side, where "away from the nearest point" would
// push it on through; so each body remembers which side of each segment it was last seen
// on, and one that turns up on the other side, within the segment's extent, goes back to
// the side it came from.
namespace {

// > 0 left of a→b, < 0 right of it, 0 on its line.
double side_of(const SegmentCollider& s, double x, double y) {
  return (s.b[0] - s.a[0]) * (y - s.a[1]) - (s.b[1] - s.a[1]) * (x - s.a[0]);
}

}  // namespace

void ConstraintProjection::project_segment(size_t j, int i, VectorRef xi) const {
  const SegmentCollider& s = colliders_.segments[j];
  const Eigen::Vector2d a(s.a[0], s.a[1]), b(s.b[0], s.b[1]);
  const Eigen::Vector2d along = b - a;
  const double length2 = along.squaredNorm();
  const Eigen::Vector2d p(xi[0], xi[1]);
  const double reach = length2 > 0 ? along.dot(p - a) / length2 : 0.0;
  const Eigen::Vector2d closest = a + std::clamp(reach, 0.0, 1.0) * along;
  const double r = radius_[i];

  const signed char before = side_[static_cast<size_t>(i) * colliders_.segments.size() + j];
  if (before != 0 && reach > 0 && reach < 1 && before * side_of(s, p.x(), p.y()) < 0) {
    // Crossed: back to the side it came from, at distance r.
    const Eigen::Vector2d normal = Eigen::Vector2d(-along.y(), along.x()).normalized();
    const Eigen::Vector2d q = closest + (before * r) * normal;
    xi[0] = q.x();
    xi[1] = q.y();
    return;
  }
  const Eigen::Vector2d away = p - closest;
  const double distance = away.norm();
  if (distance < r && distance > 0) {
    const Eigen::Vector2d q = closest + (r / distance) * away;
    xi[0] = q.x();
    xi[1] = q.y();
  } else if (distance == 0 && r > 0) {
    // Its centre on the segment: out to the side it was on, or (none yet: the start) to the one its
    // normal points to (a ball set on a segment stayed in it, whole, step after step).
    const Eigen::Vector2d normal =
        length2 > 0 ? Eigen::Vector2d(-along.y(), along.x()).normalized() : Eigen::Vector2d::UnitX();
    const Eigen::Vector2d q = closest + ((before < 0 ? -1.0 : 1.0) * r) * normal;
    xi[0] = q.x();
    xi[1] = q.y();
  }
}

// After a projection, note each body's side of each segment; a body exactly on a
// segment's line (a point resting on it) keeps the side it had.
void ConstraintProjection::remember_segment_sides(ConstVectorRef x) {
  const size_t segments = colliders_.segments.size();
  for (size_t i = 0; i * segments < side_.size(); ++i)
    for (size_t j = 0; j < segments; ++j) {
      const double side = side_of(colliders_.segments[j], x[2 * i], x[2 * i + 1]);
      if (side != 0) side_[i * segments + j] = side > 0 ? 1 : -1;
    }
}

}  // namespace motus
