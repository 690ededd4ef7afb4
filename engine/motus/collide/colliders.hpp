#pragma once
// Static colliders: walls that balls bounce off and never pass through.
//   Plane    the half-space n·x ≥ offset is free space (n a unit normal pointing into it)
//   Box      an axis-aligned container: balls stay inside [min, max]
//   Segment  a two-sided line segment from a to b (2-D scenes only)
// Each has a restitution e; a ball meeting a wall bounces with e_ball · e_wall.
#include <array>
#include <vector>

namespace motus {

struct PlaneCollider {
  std::array<double, 3> normal{0, 1, 0};
  double offset = 0;
  double restitution = 1;
};

struct BoxCollider {
  std::array<double, 3> min{0, 0, 0};
  std::array<double, 3> max{1, 1, 1};
  double restitution = 1;
};

struct SegmentCollider {
  std::array<double, 3> a{0, 0, 0};
  std::array<double, 3> b{1, 0, 0};
  double restitution = 1;
};

struct Colliders {
  std::vector<PlaneCollider> planes;
  std::vector<BoxCollider> boxes;
  std::vector<SegmentCollider> segments;

  bool empty() const { return planes.empty() && boxes.empty() && segments.empty(); }
};

}  // namespace motus
