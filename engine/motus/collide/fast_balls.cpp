// Fast balls: those that may have left their list's reach (faster than a radius per step, or pushed
// apart) look along their whole path in the grid until the lists are built again, and find each other
// in a grid of their paths in space and time (path_grid.hpp) once there are many of them.
#include "motus/collide/ball_collisions.hpp"

#include <algorithm>
#include <cmath>

#include "motus/collide/ball_collisions_tuning.hpp"

namespace motus {

using namespace ball_collisions_tuning;

template <int D>
void BallCollisions<D>::start_fast_paths() {
  // (After find_wall_events of every fast ball: their horizons.) Slabs of a typical path's time
  // (the median horizon) cut in one slab a diameter of the median path, at most kPathSlabs;
  // cells as wide as a typical path's piece in one (that piece, and a diameter), so that most
  // pieces are in one to 2^D cells. Slabs pay only where a path is long for its ball (a gas
  // that crosses its box in a step): a path of a diameter or two, cut into eight, entered and
  // looked into eight times the cells for the same candidates — 10,000 balls of radius 0.015
  // moving 1.5 radii a step took 1.0 ms a step in one slab and 6.5 ms in eight.
  fast_paths_on_ = false;
  if (fast_.size() < kPathGridFrom) return;
  auto median = [&](auto&& of) {
    path_lengths_.clear();
    for (int i : fast_) path_lengths_.push_back(of(i));
    const auto middle = path_lengths_.begin() + static_cast<std::ptrdiff_t>(path_lengths_.size() / 2);
    std::nth_element(path_lengths_.begin(), middle, path_lengths_.end(), [](double a, double b) {
      return a < b || (b != b && a == a);  // (NaN last)
    });
    return *middle;
  };
  const double path = median([&](int i) { return velocity(i).norm() * state_[i].horizon; });
  double slabs = std::floor(path / (2 * max_radius_));
  slabs = slabs >= 1 ? std::min(slabs, kPathSlabs) : 1;  // (NaN: 1)
  double slab = median([&](int i) { return state_[i].horizon; }) / slabs;
  if (!(slab > 0)) slab = h_ / slabs;  // (most fast balls at a wall now)
  path_cell_ = 2 * max_radius_ + path / slabs;
  if (!(path_cell_ > 0 && path_cell_ < INFINITY && slab < INFINITY)) return;
  // (Room for every path's entries, up to 2^D a slab and a slab's more — but not a gigabyte for a
  // million. Every bucket is emptied each step: room for nine slabs' in one took 1 M buckets,
  // 4 MB, for 10,000 balls.)
  const size_t entries =
      fast_.size() * (size_t{1} << D) * (fast_.size() < (size_t{1} << 16) ? static_cast<size_t>(slabs) + 1 : 2);
  fast_paths_.start(path_cell_, slab, entries, n_);
  fast_paths_on_ = true;
  ++counters_.path_grids;
  for (int i : fast_) enter_fast_path(i, 0);
  path_entries_ = fast_paths_.entries();
}

template <int D>
double BallCollisions<D>::path_margin(int i, const Point& p) const {
  // Its radius, and a rounding's worth (two balls that touch must have pieces that overlap).
  return radius_of(i) + kNudge * (path_cell_ + p.cwiseAbs().maxCoeff() +
                                  Eigen::Map<const Point>(v_ + D * i).cwiseAbs().maxCoeff() * h_);
}

template <int D>
void BallCollisions<D>::enter_fast_path(int i, double t) {
  // Its line from t to its horizon (after find_wall_events(i, t)).
  const Point p = position_at(i, t);
  fast_paths_.enter(i, state_[i].collisions_this_step, p, velocity(i), t, state_[i].horizon, path_margin(i, p));
}

template <int D>
void BallCollisions<D>::enter_fast_paths(int i, int k, double t) {
  // The new paths of the bodies of a contact at t (k < 0: a wall). Once the stale entries have
  // grown the grid kPathGridGrowth times, every fast ball's path from t instead.
  if (fast_paths_.entries() > kPathGridGrowth * path_entries_ + 1024) {
    fast_paths_.clear();
    for (int f : fast_) enter_fast_path(f, t);
    path_entries_ = fast_paths_.entries();
    return;
  }
  if (state_[i].fast) enter_fast_path(i, t);
  if (k >= 0 && state_[k].fast) enter_fast_path(k, t);
}

// This file's members, for each dimension the class is instantiated for (ball_collisions.cpp).
#define MOTUS_FAST_BALLS(D) \
  template void BallCollisions<D>::start_fast_paths(); \
  template double BallCollisions<D>::path_margin(int, const typename BallCollisions<D>::Point&) const; \
  template void BallCollisions<D>::enter_fast_path(int, double); \
  template void BallCollisions<D>::enter_fast_paths(int, int, double);
MOTUS_FAST_BALLS(1)
MOTUS_FAST_BALLS(2)
MOTUS_FAST_BALLS(3)
#undef MOTUS_FAST_BALLS

}  // namespace motus
