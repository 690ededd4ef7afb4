#pragma once
// Where the fast balls go in one step: a grid of space and time around their paths, so that a
// ball tests only the fast balls that pass near it at about the same time (the broad phase of
// fast against fast: O(F), not O(F²) — a scene whose balls all move farther than their radius
// in a step makes every ball fast).
//
// A path is a ball's straight line from a time t0 to a time t1 (the step's end, or sooner: see
// BallCollisions::BallState::horizon), widened by its radius. The step is cut into slabs of
// time; in each slab a path is the box of its piece of line then. Two balls can touch at a
// time T only if their boxes of T's slab overlap, and two boxes that overlap share a cell.
// (Boxes of the whole line, as this grid had once, are no use when the balls go far: in a gas
// whose every ball crosses the container in a step every box overlaps every other, and each
// contact tested every fast ball.) The cells are not stored: a cell (its integer coordinates
// and its slab) hashes to a bucket, and a bucket chains the paths entered in any of its cells,
// so a path costs a few entries however far apart the balls are, and a bucket shared by two
// cells only adds candidates, never loses one. A ball whose velocity changes within the step
// (a contact) enters its new path from then on; its old path's entries are stale (their tag is
// not the ball's any more), and are passed over. A path across more than kMaxCells cells (a
// ball much faster than the others, or at a non-finite place) is "wide": it is entered
// nowhere, and every query tests it.
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

  // Starts a step: no path, cells of `cell_size` and slabs of `slab` seconds (a typical path
  // spans a few slabs, and in each one or two cells along each axis), room for about `entries`
  // entries without a bucket growing long.
  void start(double cell_size, double slab, size_t entries, int bodies) {
    inverse_cell_size_ = 1 / cell_size;
    slab_ = slab;
    inverse_slab_ = 1 / slab;
    size_t buckets = 64;
    while (buckets < 2 * entries) buckets *= 2;
    head_.resize(buckets);  // (every bucket is emptied by clear: once a step, not twice)
    mask_ = buckets - 1;
    clear();
    if (seen_.size() != static_cast<size_t>(bodies)) seen_.assign(static_cast<size_t>(bodies), 0), stamp_ = 0;
  }

  // Forgets every path (and keeps the buckets).
  void clear() {
    std::fill(head_.begin(), head_.end(), -1);
    entries_.clear();
    wide_.clear();
  }

  size_t entries() const { return entries_.size(); }

  // Enters ball i's path: from p at time t0 with velocity u until t1, widened by `margin`.
  // `tag` tells its entries from those of the ball's later paths.
  void enter(int i, unsigned tag, const Point& p, const Point& u, double t0, double t1, double margin) {
    if (!place(p, u, t0, t1, margin)) {
      wide_.push_back({i, tag, -1});
      return;
    }
    for (const Piece& piece : pieces_)
      for_cells(piece, [&](std::uint64_t bucket) {
        entries_.push_back({i, tag, head_[bucket]});
        head_[bucket] = static_cast<int>(entries_.size()) - 1;
      });
  }

  // Calls visit(k) once for every ball whose path (its entry tagged tag(k)) may come near the
  // path from p at t0 with velocity u until t1, widened by `margin` (and for every wide path);
  // returns the cells looked into. A wide path visits nothing and returns −1: its ball is to be
  // tested against every fast ball.
  template <class Tag, class Visit>
  long for_near(const Point& p, const Point& u, double t0, double t1, double margin, Tag&& tag, Visit&& visit) {
    if (!place(p, u, t0, t1, margin)) return -1;
    if (++stamp_ == 0) std::fill(seen_.begin(), seen_.end(), 0u), stamp_ = 1;
    auto once = [&](const Entry& e) {
      const auto k = static_cast<size_t>(e.ball);
      if (seen_[k] != stamp_ && e.tag == tag(e.ball)) seen_[k] = stamp_, visit(e.ball);
    };
    for (const Entry& e : wide_) once(e);
    long cells = 0;
    for (const Piece& piece : pieces_)
      for_cells(piece, [&](std::uint64_t bucket) {
        ++cells;
        for (int e = head_[bucket]; e >= 0; e = entries_[static_cast<size_t>(e)].next)
          once(entries_[static_cast<size_t>(e)]);
      });
    return cells;
  }

private:
  using Cell = std::array<std::int64_t, D>;
  struct Entry {
    int ball;
    unsigned tag;
    int next;  // the bucket's entry before it
  };
  struct Piece {
    Cell low, high;
    std::int64_t slab;
  };
  static constexpr std::int64_t kMaxCells = 512;
  // (Cells farther out than this are not hashed: a box there is wide.)
  static constexpr double kFarthest = 1e15;

  // The boxes of the path's pieces, slab by slab (the piece from a to b: the slab's ends, within
  // [t0, t1]) into pieces_; false when they have more than kMaxCells cells or are not finite.
  bool place(const Point& p, const Point& u, double t0, double t1, double margin) {
    pieces_.clear();
    t1 = std::max(t0, t1);
    const double s0 = std::floor(t0 * inverse_slab_), s1 = std::floor(t1 * inverse_slab_);
    if (!(s0 >= 0 && s1 - s0 < static_cast<double>(kMaxCells))) return false;  // (NaN too)
    std::int64_t count = 0;
    for (auto s = static_cast<std::int64_t>(s0), last = static_cast<std::int64_t>(s1); s <= last; ++s) {
      const double a = std::max(t0, static_cast<double>(s) * slab_), b = std::max(a, std::min(t1, static_cast<double>(s + 1) * slab_));
      const Point pa = p + u * (a - t0), pb = p + u * (b - t0);
      Piece piece;
      piece.slab = s;
      std::int64_t cells = 1;
      for (int k = 0; k < D; ++k) {
        const double l = std::floor((std::min(pa[k], pb[k]) - margin) * inverse_cell_size_);
        const double h = std::floor((std::max(pa[k], pb[k]) + margin) * inverse_cell_size_);
        if (!(l >= -kFarthest && h <= kFarthest && l <= h)) return false;  // (NaN too)
        piece.low[k] = static_cast<std::int64_t>(l);
        piece.high[k] = static_cast<std::int64_t>(h);
        cells *= piece.high[k] - piece.low[k] + 1;
        if (cells > kMaxCells) return false;
      }
      count += cells;
      if (count > kMaxCells) return false;
      pieces_.push_back(piece);
    }
    return true;
  }

  template <class F>
  void for_cells(const Piece& piece, F&& f) const {
    const Cell &a = piece.low, &b = piece.high;
    Cell c = a;
    for (;;) {
      // (A hash of the cell's coordinates and slab: large odd multipliers, mixed down.)
      std::uint64_t key = static_cast<std::uint64_t>(piece.slab) * 0xD6E8FEB86659FD93ull;
      for (int k = 0; k < D; ++k) key = (key ^ static_cast<std::uint64_t>(c[k])) * 0x9E3779B97F4A7C15ull;
      f((key ^ (key >> 29)) & mask_);
      int k = 0;
      while (k < D && c[k] == b[k]) c[k] = a[k], ++k;  // an odometer over the box's cells
      if (k >= D) break;
      ++c[k];
    }
  }

  double inverse_cell_size_ = 1, slab_ = 1, inverse_slab_ = 1;
  std::vector<Piece> pieces_;  // (place's)
  std::vector<int> head_;  // per bucket: its last entry, −1 for none
  std::uint64_t mask_ = 0;
  std::vector<Entry> entries_;
  std::vector<Entry> wide_;
  std::vector<unsigned> seen_;  // per ball: the query that last visited it
  unsigned stamp_ = 0;
};

}  // namespace motus
