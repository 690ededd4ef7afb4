#pragma once
// Where the fast balls go in one step: a grid of the boxes around their paths, so that a ball
// tests only the fast balls whose paths pass near its own (the broad phase of fast against fast:
// O(F), not O(F²) — a scene whose balls all move farther than their radius in a step makes
// every ball fast).
//
// A path is the box of a ball's straight line from a time t to the step's end, widened by its
// radius. Two balls can touch within the step only if their boxes overlap, and two boxes that
// overlap share a cell. The cells are not stored: a cell (its integer coordinates) hashes to a
// bucket, and a bucket chains the paths entered in any of its cells, so a path costs a few
// entries however far apart the balls are, and a bucket shared by two cells only adds
// candidates, never loses one. A ball whose velocity changes within the step (a contact)
// enters its new path from then on; its old path's entries stay, and only add candidates.
// A path across more than kMaxCells cells (a ball much faster than the others, or at a
// non-finite place) is "wide": it is entered nowhere, and every query tests it.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace motus {

template <int D>
class PathGrid {
public:
  using Point = Eigen::Matrix<double, D, 1>;

  // Starts a step: no path, cells of `cell_size` (the boxes of a typical path span one or two
  // cells along each axis), room for about `paths` paths without a bucket growing long.
  void start(double cell_size, size_t paths, int bodies) {
    inverse_cell_size_ = 1 / cell_size;
    size_t buckets = 64;
    while (buckets < 2 * paths * (size_t{1} << D)) buckets *= 2;
    head_.assign(buckets, -1);
    mask_ = buckets - 1;
    ball_.clear();
    next_.clear();
    wide_.clear();
    if (seen_.size() != static_cast<size_t>(bodies)) seen_.assign(static_cast<size_t>(bodies), 0), stamp_ = 0;
  }

  // Enters ball i's path: the box [low, high] (its line, widened by its radius).
  void enter(int i, const Point& low, const Point& high) {
    Cell a, b;
    if (!cells_of(low, high, a, b)) {
      wide_.push_back(i);
      return;
    }
    for_cells(a, b, [&](std::uint64_t bucket) {
      ball_.push_back(i);
      next_.push_back(head_[bucket]);
      head_[bucket] = static_cast<int>(ball_.size()) - 1;
    });
  }

  // Calls visit(k) once for every ball whose path may overlap the box [low, high] (and for every
  // wide path); returns the cells looked into. A wide box visits nothing and returns −1: its
  // ball is to be tested against every fast ball.
  template <class Visit>
  long for_near(const Point& low, const Point& high, Visit&& visit) {
    Cell a, b;
    if (!cells_of(low, high, a, b)) return -1;
    if (++stamp_ == 0) std::fill(seen_.begin(), seen_.end(), 0u), stamp_ = 1;
    auto once = [&](int k) {
      if (seen_[static_cast<size_t>(k)] != stamp_) seen_[static_cast<size_t>(k)] = stamp_, visit(k);
    };
    for (int k : wide_) once(k);
    long cells = 0;
    for_cells(a, b, [&](std::uint64_t bucket) {
      ++cells;
      for (int e = head_[bucket]; e >= 0; e = next_[static_cast<size_t>(e)]) once(ball_[static_cast<size_t>(e)]);
    });
    return cells;
  }

private:
  using Cell = std::array<std::int64_t, D>;
  static constexpr std::int64_t kMaxCells = 64;
  // (Cells farther out than this are not hashed: a box there is wide.)
  static constexpr double kFarthest = 1e15;

  // The cells of a box, from a to b; false when it spans more than kMaxCells or is not finite.
  bool cells_of(const Point& low, const Point& high, Cell& a, Cell& b) const {
    std::int64_t count = 1;
    for (int k = 0; k < D; ++k) {
      const double l = std::floor(low[k] * inverse_cell_size_), h = std::floor(high[k] * inverse_cell_size_);
      if (!(l >= -kFarthest && h <= kFarthest && l <= h)) return false;  // (NaN too)
      a[k] = static_cast<std::int64_t>(l);
      b[k] = static_cast<std::int64_t>(h);
      count *= b[k] - a[k] + 1;
      if (count > kMaxCells) return false;
    }
    return true;
  }

  template <class F>
  void for_cells(const Cell& a, const Cell& b, F&& f) const {
    Cell c = a;
    for (;;) {
      // (A hash of the cell's coordinates: large odd multipliers, mixed down.)
      std::uint64_t key = 0;
      for (int k = 0; k < D; ++k) key = (key ^ static_cast<std::uint64_t>(c[k])) * 0x9E3779B97F4A7C15ull;
      f((key ^ (key >> 29)) & mask_);
      int k = 0;
      while (k < D && c[k] == b[k]) c[k] = a[k], ++k;  // an odometer over the box's cells
      if (k >= D) break;
      ++c[k];
    }
  }

  double inverse_cell_size_ = 1;
  std::vector<int> head_;         // per bucket: its last entry, −1 for none
  std::uint64_t mask_ = 0;
  std::vector<int> ball_, next_;  // per entry: the ball, and the bucket's entry before it
  std::vector<int> wide_;
  std::vector<unsigned> seen_;  // per ball: the query that last visited it
  unsigned stamp_ = 0;
};

}  // namespace motus
