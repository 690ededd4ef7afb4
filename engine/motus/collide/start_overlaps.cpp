// The scene's own overlap, removed whole before its first step (ball_collisions.hpp): the walls and the
// listed pairs swept in turn until nothing overlaps.
#include "motus/collide/ball_collisions.hpp"

#include <algorithm>
#include <cmath>

#include "motus/collide/ball_collisions_tuning.hpp"

namespace motus {

using namespace ball_collisions_tuning;

// The lists on positions they have never seen: at the scene's start, the scene's own overlap is
// removed first, whole. The steps' start removes overlap in one pass, walls and then pairs, which
// is enough for rounding; but a pair moved apart by a scene's overlap may push a ball into a wall
// (or into a third ball) that the pass has done with, and it stayed there, a step at a time
// coming out (three balls in a row 0.1 m into each other beside a wall: the first 0.05 m into the
// wall after the first step, 0.006 m after the tenth). A start with nothing to move (every shipped
// scene) costs one look at the listed pairs and the walls, and keeps the lists just built.
template <int D>
void BallCollisions<D>::build_lists_at_start() {
  build_lists();
  if (settle_overlaps()) build_lists();  // from where the balls are now, with the steps' skin
}

// The walls and the listed pairs swept in turn, each body pushed out of the walls it is in and each
// overlapping pair moved apart (as at a step's start: along the normal, mass-weighted, positions
// only), until a sweep finds nothing to move, or the sweeps or the tests run out (kSettleSweeps,
// kSettleWork: no room for the balls; the steps then go on as before). Whether it moved anything.
//
// Each sweep tests what a step's start tests: slow balls against the box faces they are listed
// near (near_faces_) and the listed pairs, every body against the general planes and the segments,
// fast balls and points against every wall (an overlap with a fast ball is its contact: it is not
// moved apart). The lists and near_faces_ hold while no ball has been pushed farther than half
// their skin since they were built; a ball pushed farther may have come near balls and faces that
// are not on them, and they are built again, from where the balls are (with a skin of at least the
// largest radius: a build at rest has none). So a sweep that finds nothing has looked at every
// pair and wall that could overlap: nothing does.
template <int D>
bool BallCollisions<D>::settle_overlaps() {
  const int plane_count = static_cast<int>(planes_.size());
  const bool every_body = !segments_.empty() || !fast_.empty() || !points_.empty() ||
                          std::any_of(planes_.begin(), planes_.end(), [](const Plane& p) { return p.axis < 0; });
  const long walls_per_body = every_body ? plane_count + static_cast<long>(segments_.size()) : 0;
  // How far each ball is from where it was when the lists were built (D numbers a ball; sized at
  // the first push, for most starts have none), and the farthest.
  std::vector<double> from_build;
  double farthest = 0;
  bool settled = false;
  long work = 0;  // tests made
  for (int sweep = 0; sweep < kSettleSweeps && work < kSettleWork; ++sweep) {
    work += static_cast<long>(near_faces_.size()) + pair_count_ + n_ * walls_per_body;
    bool moved = false;
    auto note = [&](int i, const Point& before) {  // body i was at `before` until a push
      if (radius_of(i) <= 0) return;  // (a point is on no list)
      if (from_build.empty()) from_build.assign(static_cast<size_t>(n_) * D, 0.0);
      auto offset = Eigen::Map<Point>(from_build.data() + static_cast<size_t>(D) * static_cast<size_t>(i));
      offset += position(i) - before;
      farthest = std::max(farthest, offset.norm());
    };
    auto out_of_wall = [&](int i, const Point& before, double distance) {
      if (!(distance > 0)) return;
      // (A wall's push this small is rounding, in the contact distances or the position; a pair's
      // never is: it is tested with the same slack.)
      moved = moved || distance > kOverlapSlack * (2 * max_radius_ + before.cwiseAbs().maxCoeff());
      note(i, before);
    };
    for (const NearFace& f : near_faces_) {
      const Point before = position(f.ball);
      out_of_wall(f.ball, before, push_out_of_plane(f.ball, f.wall));
    }
    if (every_body) {
      for (int i = 0; i < n_; ++i) {
        const bool listed = radius_of(i) > 0 && !state_[i].fast;  // (its box faces: near_faces_)
        for (int w = 0; w < plane_count; ++w) {
          if (listed && planes_[static_cast<size_t>(w)].axis >= 0) continue;
          const Point before = position(i);
          out_of_wall(i, before, push_out_of_plane(i, w));
        }
        if constexpr (D == 2) {
          for (const Segment& s : segments_) {
            const Point before = position(i);
            out_of_wall(i, before, push_off_segment(i, s));
          }
        }
      }
    }
    for (int q = 0; q < pair_count_; ++q) {
      const int i = pair_i_[static_cast<size_t>(q)], k = pair_k_[static_cast<size_t>(q)];
      const double R = radius_of(i) + radius_of(k);
      const Point before_i = position(i), before_k = position(k);
      if (!((before_k - before_i).squaredNorm() < R * R * (1 - kOverlapSlack))) continue;  // (as exact())
      const auto [by_i, by_k] = push_apart(i, k);
      if (!(by_i > 0 || by_k > 0)) continue;
      moved = true;
      note(i, before_i), note(k, before_k);
    }
    if (!moved) return settled;
    settled = true;
    if (farthest > 0.5 * skin_) {
      build_lists(max_radius_);
      work += kSettleBuildWork * n_;
      std::fill(from_build.begin(), from_build.end(), 0.0);
      farthest = 0;
    }
  }
  return settled;
}

// This file's members, for each dimension the class is instantiated for (ball_collisions.cpp).
#define MOTUS_START_OVERLAPS(D) \
  template void BallCollisions<D>::build_lists_at_start(); \
  template bool BallCollisions<D>::settle_overlaps();
MOTUS_START_OVERLAPS(1)
MOTUS_START_OVERLAPS(2)
MOTUS_START_OVERLAPS(3)
#undef MOTUS_START_OVERLAPS

}  // namespace motus
