// The neighbour lists (ball_collisions.hpp, step 1): every two slow balls closer than r_a + r_b + skin,
// listed from a uniform grid of cells 2·r_max + skin wide, and built again when the fastest slow ball
// may have used up half the skin. A step tests only the listed pairs, batch by batch, and of a batch only
// the gap classes its balls can have closed by the step's end.
#include "motus/collide/ball_collisions.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "motus/collide/ball_collisions_tuning.hpp"

namespace motus {

using namespace ball_collisions_tuning;

namespace {

// `table` = n zeros, its room grown at least twofold when it must grow: a grid that widens build
// after build (two balls flying apart) then allocates a few times, not at nearly every build (69
// times in head_on's first 20,000 steps with assign's exact sizes).
template <class Table>  // std::vector<int> or BigArray<int>
void assign_zeros(Table& table, size_t n) {
  if (table.capacity() < n) table.reserve(std::max(n, 2 * table.capacity()));
  table.assign(n, 0);
}


}  // namespace

template <int D>
double BallCollisions<D>::fastest_slow_speed(double h) {
  // The fastest slow ball's speed, and the fast balls. (Branch-free and, when every body is a
  // ball, over the velocities in order: the compiler vectorises it.)
  const double limit2 = max_radius_ * max_radius_ / (h * h);
  const double* v = v_;
  auto speed2 = [v](int i) {
    double s2 = 0;
    for (int k = 0; k < D; ++k) s2 += v[D * i + k] * v[D * i + k];
    return s2;
  };
  double slowest2 = 0;
  long fast = 0;
  auto take = [&](double s2) {
    const bool slow = s2 <= limit2;  // (a NaN speed is fast)
    slowest2 = std::max(slowest2, slow ? s2 : 0.0);
    fast += !slow;
  };
  if (points_.empty()) {
    for (int i = 0; i < n_; ++i) take(speed2(i));
  } else {
    for (int i : balls_) take(speed2(i));
  }
  if (fast > 0)
    for (int i : balls_)
      if (!(speed2(i) <= limit2)) state_[i].fast = true, fast_.push_back(i);
  return std::sqrt(slowest2);
}

template <int D>
bool BallCollisions<D>::lists_hold() const {
  // Built, on these positions; no ball still on them may have come within reach of one that is
  // not on its list by the end of this step; and few enough balls have left them that their
  // searches along their paths cost less than a new build.
  return lists_built_ && lists_x_ == x_ && moved_since_build_ + sweep_ <= 0.5 * skin_ &&
         escaped_.size() <= 8 + balls_.size() / 4096;
}

template <int D>
void BallCollisions<D>::build_lists(double least_skin) {
  for (int i : escaped_) state_[i].escaped = false;
  escaped_.clear();
  for (int i : fast_) state_[i].escaped = true, escaped_.push_back(i);  // not in the grid, nor on the lists
  skin_ = std::max({std::min(2 * kSkinSteps * sweep_, max_radius_), 2 * sweep_, least_skin});
  moved_since_build_ = 0;
  lists_built_ = true;
  lists_x_ = x_;
  // One pass over the slow balls for their extent, for the grid, and for the faces of boxes
  // they are near: a ball farther inside a face than r + skin/2 cannot reach it before the
  // next build. Most balls are near no face: a window per axis, inside every face's reach
  // (widened by a rounding's worth: the face's own test decides), lets them by with 2·D
  // comparisons and no branch; the few outside it are tested face by face.
  near_faces_.clear();
  const Plane* planes = planes_.data();
  const int plane_count = static_cast<int>(planes_.size());
  // (A box's faces follow the general planes: see the constructor.)
  const int first_face = static_cast<int>(
      std::find_if(planes_.begin(), planes_.end(), [](const Plane& p) { return p.axis >= 0; }) - planes_.begin());
  const double reach = max_radius_ + 0.5 * skin_ + kNudge * (2 * max_radius_ + skin_);
  double inner_low[D], inner_high[D];
  for (int k = 0; k < D; ++k) inner_low[k] = -INFINITY, inner_high[k] = INFINITY;
  for (int w = first_face; w < plane_count; ++w) {
    const int k = planes[w].axis;
    const double bound = planes[w].sign * planes[w].offset + planes[w].sign * reach;  // where its reach ends
    const double rounding = 1e-12 * (std::abs(bound) + reach);
    if (planes[w].sign > 0) {
      inner_low[k] = std::max(inner_low[k], bound + rounding);
    } else {
      inner_high[k] = std::min(inner_high[k], bound - rounding);
    }
  }
  const double* x = x_;
  double low[D], high[D];
  for (int k = 0; k < D; ++k) low[k] = INFINITY, high[k] = -INFINITY;
  auto outside_window = [&](int i) {
    bool outside = false;
    for (int k = 0; k < D; ++k) outside |= (x[D * i + k] < inner_low[k]) | (x[D * i + k] > inner_high[k]);
    return outside;
  };
  auto note_near_faces = [&](int i) {
    for (int w = first_face; w < plane_count; ++w)
      if (planes[w].sign * x[D * i + planes[w].axis] - planes[w].offset < reach) near_faces_.push_back({i, w});
  };
  int from = 0;  // (the balls before it are done)
  if (fast_.empty() && points_.empty()) {
    // Every body is a slow ball: the positions in order, two balls at a time, as one array of
    // 2·D numbers — whole SIMD registers in 2-D and in 3-D, where one ball's three are not. The
    // pairs with a ball outside the window (or a NaN) are noted, and looked at one ball at a
    // time after the pass: with no call in it, the extent stays in registers. (min and max keep
    // std::min's and std::max's choice when a position is NaN.)
    using TwoBalls = Eigen::Array<double, 2 * D, 1>;
    TwoBalls lowest = TwoBalls::Constant(INFINITY), highest = TwoBalls::Constant(-INFINITY);
    TwoBalls window_low, window_high;
    for (int k = 0; k < D; ++k) {
      window_low[k] = window_low[D + k] = inner_low[k];
      window_high[k] = window_high[D + k] = inner_high[k];
    }
    if (outside_window_.size() < static_cast<size_t>(n_ / 2)) outside_window_.resize(static_cast<size_t>(n_ / 2));
    int* noted = outside_window_.data();
    int count = 0;
    for (; from + 1 < n_; from += 2) {
      const TwoBalls p = Eigen::Map<const TwoBalls>(x + D * from);
      lowest = lowest.min(p);
      highest = highest.max(p);
      const double inside = (p - window_low).min(window_high - p).minCoeff();  // ≥ 0 inside the window
      noted[count] = from;
      count += !(inside >= 0);
    }
    for (int k = 0; k < D; ++k) {
      low[k] = std::min(lowest[k], lowest[D + k]);
      high[k] = std::max(highest[k], highest[D + k]);
    }
    for (int a = 0; a < count; ++a)
      for (const int i : {noted[a], noted[a] + 1})
        if (outside_window(i)) note_near_faces(i);
  }
  auto take = [&](int i) {  // one ball
    for (int k = 0; k < D; ++k) {
      low[k] = std::min(low[k], x[D * i + k]);
      high[k] = std::max(high[k], x[D * i + k]);
    }
    if (outside_window(i)) [[unlikely]]
      note_near_faces(i);
  };
  if (from > 0) {
    for (int i = from; i < n_; ++i) take(i);  // (the last, when the count is odd)
  } else {
    for_slow(take);
  }
  for (int k = 0; k < D; ++k) grid_low_[k] = low[k], grid_high_[k] = high[k];
  pair_count_ = 0;
  listed_ = 0;
  gap_sorted_ = 0;
  if (balls_.size() >= 2) {
    build_grid();             // (a big grid lists most of its pairs as it sorts: see build_grid)
    list_pairs(slow_count_);  // (the rest)
  }
  sort_by_gap(true);
  const int batches = gap_sorted_;
  // (With no pairs, sort_by_gap has sized no frontier.)
  if (frontier_.size() < static_cast<size_t>(batches) + 1) frontier_.resize(static_cast<size_t>(batches) + 1);
  // The frontiers: the lowest of each batch and of every batch after it.
  frontier_[static_cast<size_t>(batches)] = n_;
  for (int b = batches - 1; b >= 0; --b)
    frontier_[static_cast<size_t>(b)] = std::min(frontier_[static_cast<size_t>(b)], frontier_[static_cast<size_t>(b) + 1]);
  // Both ways, by ball: ball i's neighbours, for the searches after its contacts.
  neighbour_start_.assign(static_cast<size_t>(n_) + 2, 0);
  int* start = neighbour_start_.data();
  const size_t pairs = static_cast<size_t>(pair_count_);
  for (size_t q = 0; q < pairs; ++q) ++start[pair_i_[q] + 2], ++start[pair_k_[q] + 2];
  for (int b = 2; b < n_ + 2; ++b) start[b] += start[b - 1];
  if (neighbours_.size() < 2 * pairs) neighbours_.resize(2 * pairs);
  for (size_t q = 0; q < pairs; ++q) {
    neighbours_[static_cast<size_t>(start[pair_i_[q] + 1]++)] = pair_k_[q];
    neighbours_[static_cast<size_t>(start[pair_k_[q] + 1]++)] = pair_i_[q];
  }
}

template <int D>
void BallCollisions<D>::sort_by_gap(bool last) {
  // Each of the pair pass's batches by gap class (see kGapClasses): a stable counting sort, as
  // soon as the batch is listed (its pairs still in cache). A pair's class: how many of the
  // classes' lower ends (r_a + r_b + c · width) its distance reaches. And each batch's lowest
  // body number, for the pass's frontiers (see frontier_).
  const double class_width = skin_ / kGapClasses;
  for (;;) {
    const int b = gap_sorted_, from = b * kBatch, to = std::min(pair_count_, from + kBatch);
    if (to - from < kBatch && !(last && to > from)) return;
    // (Grown, never shrunk: once warm, a build allocates nothing. The frontiers have one more,
    // for the end: see build_lists.)
    if (class_start_.size() < static_cast<size_t>(b + 1) * (kGapClasses + 1))
      class_start_.resize(2 * static_cast<size_t>(b + 1) * (kGapClasses + 1));
    if (frontier_.size() < static_cast<size_t>(b) + 2) frontier_.resize(2 * static_cast<size_t>(b) + 2);
    int count[kGapClasses + 1] = {};
    unsigned char gap_class[kBatch];
    int lowest = n_;
    for (int q = from; q < to; ++q) {
      const int i = pair_i_[static_cast<size_t>(q)], k = pair_k_[static_cast<size_t>(q)];
      lowest = std::min({lowest, i, k});
      const double R = radius_of(i) + radius_of(k);
      const double d2 = pair_d2_[static_cast<size_t>(q)];
      int c = 0;
      for (int u = 1; u < kGapClasses; ++u) c += d2 >= (R + u * class_width) * (R + u * class_width);
      gap_class[q - from] = static_cast<unsigned char>(c);
      ++count[c + 1];
    }
    int* starts = class_start_.data() + static_cast<size_t>(b) * (kGapClasses + 1);
    starts[0] = from;
    for (int c = 1; c <= kGapClasses; ++c) starts[c] = starts[c - 1] + count[c];
    int at[kGapClasses];
    for (int c = 0; c < kGapClasses; ++c) at[c] = starts[c] - from;
    int block_i[kBatch], block_k[kBatch];
    for (int q = from; q < to; ++q) {
      const int c = gap_class[q - from];
      block_i[at[c]] = pair_i_[static_cast<size_t>(q)], block_k[at[c]] = pair_k_[static_cast<size_t>(q)], ++at[c];
    }
    std::copy(block_i, block_i + (to - from), pair_i_.begin() + from);
    std::copy(block_k, block_k + (to - from), pair_k_.begin() + from);
    frontier_[static_cast<size_t>(b)] = lowest;
    ++gap_sorted_;
  }
}

template <int D>
void BallCollisions<D>::build_grid() {
  ++counters_.grid_builds;
  // Two balls on the lists that were within r_a + r_b + skin at the build are in the same or
  // neighbouring cells.
  cell_size_ = 2 * max_radius_ + skin_;
  const long slow = static_cast<long>(balls_.size() - fast_.size());
  if (slow == 0) grid_low_ = grid_high_ = Point::Zero();
  const Point low = grid_low_, high = grid_high_;
  // A position at infinity (or NaN) has no cell: without this the sizing below never ends.
  if (!low.allFinite() || !high.allFinite() || !std::isfinite(cell_size_))
    throw std::runtime_error("a body's position is no longer finite: the collision grid cannot place it");
  // Finite positions so far apart that their distance is not (±1e308): no cell size spans them.
  if (!(high - low).allFinite())
    throw std::runtime_error("the bodies are too far apart for the collision grid (their positions span more than a "
                             "double can hold)");
  // Dense cells over the balls' extent, but never many more cells than balls (a sparse
  // scene gets bigger cells instead).
  // (3-D needs the more: a cubic lattice of spacing 4r has ~7 cells of the smallest size
  // per ball, and bigger cells cost more pair tests than the cells they save.)
  const double budget = (D == 3 ? 8.0 : 4.0) * static_cast<double>(slow) + 64;
  for (;;) {
    double total = 1;
    for (int k = 0; k < D; ++k) {
      dims_[k] = static_cast<int>(std::min((high[k] - low[k]) / cell_size_, 1e6)) + 1;
      total *= dims_[k];
    }
    if (total <= budget) break;
    cell_size_ *= std::pow(total / budget, 1.0 / D) * 1.01;
  }
  inverse_cell_size_ = 1 / cell_size_;
  origin_ = low - Point::Constant(cell_size_);  // one cell of padding below
  int cells = 1;
  for (int k = 0; k < D; ++k) {
    dims_[k] += 2;  // and one above
    stride_[k] = cells;
    cells *= dims_[k];
  }
  // The neighbour cells as rows, each given by the index offset of its middle cell: three
  // cells side by side along x are consecutive in the sorted array, so a row is one range
  // of balls (in the order that visiting its cells one by one would give). The "forward"
  // half of the 3^(D-1) rows (last non-zero step +1) visits every pair of neighbouring cells
  // once. In 2-D that is the rest of the ball's own row and one row above.
  forward_rows_.clear();
  int total = 1;
  for (int k = 0; k < D; ++k) total *= 3;
  for (int code = 0; code < total; ++code) {
    int offset = 0, leading = 0;
    for (int k = 0, c = code; k < D; ++k, c /= 3) {
      offset += (c % 3 - 1) * stride_[k];
      if (k > 0 && c % 3 != 1) leading = c % 3 - 1;
    }
    if (leading > 0 && code % 3 == 1) forward_rows_.push_back(offset);  // the middle cell of a row above
  }
  if (forward_rows_.size() != static_cast<size_t>(kForwardRows<D>)) throw std::logic_error("the grid's forward rows");
  max_forward_ = forward_rows_.empty() ? 0 : *std::max_element(forward_rows_.begin(), forward_rows_.end());

  // Counting sort by cell. Big grids in two levels, so that the cells' array is written once and
  // never read back while sorting: first by block of kBlock consecutive cells (few
  // blocks: their counts stay in cache), then within each block by cell, with counts in
  // a small local array, writing the block's cell starts as it goes. At a million balls
  // the cells' array is tens of MB, and a one-level sort (zero it, count into it, sum it,
  // place from it) streams it through memory four times. Both levels are stable, so
  // within a cell the balls keep balls_'s order (as a one-level sort would leave them),
  // and the events come in the same order. Afterwards cell c holds sorted_[cell_start_[c]
  // .. cell_start_[c + 1]).
  // A big grid's pairs are listed as its blocks are placed, a few blocks behind (as soon as a
  // ball's forward rows are placed): the cells, the balls' numbers and their positions are
  // still in cache then. Listed after the sort, at a million balls, they come back from memory.
  if (cells <= kSmallGrid) {
    // Cells that fit in cache: one level (zero, count, sum, place — each at cache speed).
    assign_zeros(cell_start_, static_cast<size_t>(cells) + 2);
    for_slow([&](int i) {
      ball_cell_[i] = cell_index(cell_of(position(i)));
      ++cell_start_[static_cast<size_t>(ball_cell_[i]) + 2];
    });
    int sum = 0;  // (in a register: the running sum is one long dependency chain)
    for (int c = 2; c < cells + 2; ++c) cell_start_[c] = sum += cell_start_[c];
    sorted_.resize(static_cast<size_t>(slow) + kWindow);  // (padding: the pair search copies kWindow at a time)
    slow_count_ = static_cast<int>(slow);
    for_slow([&](int i) { sorted_[cell_start_[ball_cell_[i] + 1]++] = i; });
    return;
  }
  constexpr int kBlockBits = 12, kBlock = 1 << kBlockBits;
  const int blocks = (cells + kBlock - 1) >> kBlockBits;
  // Level one: count per block (into slot b + 2), sum, place at slot b + 1 (as in a
  // one-level counting sort); block b then spans by_block_[block_start_[b] ..
  // block_start_[b + 1]).
  assign_zeros(block_start_, static_cast<size_t>(blocks) + 2);
  for_slow([&](int i) {
    const int c = cell_index(cell_of(position(i)));
    ball_cell_[i] = c;
    ++block_start_[static_cast<size_t>(c >> kBlockBits) + 2];
  });
  int sum = 0;
  for (int b = 2; b < blocks + 2; ++b) block_start_[b] = sum += block_start_[b];
  by_block_.resize(static_cast<size_t>(slow));
  for_slow([&](int i) { by_block_[block_start_[(ball_cell_[i] >> kBlockBits) + 1]++] = {i, ball_cell_[i]}; });
  // Level two, block by block.
  sorted_.resize(static_cast<size_t>(slow) + kWindow);
  slow_count_ = static_cast<int>(slow);
  cell_start_.resize(static_cast<size_t>(cells) + 2);
  local_count_.resize(kBlock);
  int* count = local_count_.data();
  for (int b = 0; b < blocks; ++b) {
    const int first_cell = b << kBlockBits, block_cells = std::min(kBlock, cells - first_cell);
    const int from = block_start_[b], to = block_start_[b + 1];
    std::fill(count, count + block_cells, 0);
    for (int s = from; s < to; ++s) ++count[by_block_[s].cell & (kBlock - 1)];
    // Cell j's insertion point is starts[j + 1], which placing moves on to cell j + 1's start
    // (as in the one-level sort; one store a cell). The block's last one is the next block's first start.
    int* starts = cell_start_.data() + first_cell;
    starts[0] = from;
    int run = from;
    for (int j = 0; j < block_cells; ++j) starts[j + 1] = run, run += count[j];
    for (int s = from; s < to; ++s) {
      const int ball = by_block_[s].ball;
      sorted_[starts[(by_block_[s].cell & (kBlock - 1)) + 1]++] = ball;
      __builtin_prefetch(x_ + D * ball);  // (for the listing, a few blocks on)
    }
    // The balls whose forward rows are all placed now (cells up to the block's end), listed.
    const int last_cell = first_cell + block_cells - max_forward_ - 2;
    if (last_cell >= 0) list_pairs(cell_start_[static_cast<size_t>(last_cell) + 1]);
  }
  cell_start_[cells] = cell_start_[cells + 1] = static_cast<int>(slow);
}

template <int D>
void BallCollisions<D>::list_pairs(int until) {
  // The pairs of the balls at sorted_[listed_ .. until), after those listed before; each batch
  // of the pair pass sorted by gap (sort_by_gap) as soon as it is whole.
  if (until <= listed_) return;
  // Every pair of slow balls closer than r_a + r_b + skin, from the grid: each ball against the
  // later balls of its own cell and of the next cell along x, and the balls of its forward rows.
  // Batch by batch, branch-free: list the batch's candidates (each range of sorted_ copied
  // kWindow entries at once, whatever its length, the list's end moved on by that length),
  // then keep those within reach.
  const int* sorted = sorted_.data();
  const int* cell_start = cell_start_.data();
  const int* forward_rows = forward_rows_.data();
  const double* x = x_;
  const double* radius = radius_.data();
  const bool uniform = uniform_radius_;
  const double margin = skin_ + kNudge * cell_size_;  // (rounding in positions must not cut a pair)
  // A batch's list has room for kBatch pairs and one more ball's ranges at kWindow each.
  const size_t room = static_cast<size_t>(kBatch + (kForwardRows<D> + 1) * kWindow);
  if (candidate_i_.size() < room) candidate_i_.resize(room), candidate_k_.resize(room);
  int* ci = candidate_i_.data();
  int* ck = candidate_k_.data();
  int n = 0;  // candidates listed in this batch
  auto list = [&](int i, int from, int to) {
    const int count = to - from;
    if (count <= kWindow) [[likely]] {
      std::memcpy(ck + n, sorted + from, sizeof(int) * kWindow);  // (sorted_ has kWindow entries of padding)
      for (int w = 0; w < kWindow; ++w) ci[n + w] = i;
      n += count;
      return;
    }
    // A crowded range (a dense pack): the list grows.
    if (candidate_i_.size() < static_cast<size_t>(n + count) + room) {
      const size_t grown = 2 * (static_cast<size_t>(n + count) + room);
      candidate_i_.resize(grown), candidate_k_.resize(grown);
      ci = candidate_i_.data(), ck = candidate_k_.data();
    }
    for (int u = from; u < to; ++u) ci[n] = i, ck[n] = sorted[u], ++n;
  };
  size_t kept = static_cast<size_t>(pair_count_);
  auto keep_within_reach = [&] {
    if (pair_i_.size() < kept + static_cast<size_t>(n)) {
      const size_t grown = 2 * (kept + static_cast<size_t>(n));
      pair_i_.resize(grown), pair_k_.resize(grown), pair_d2_.resize(grown);
    }
    int* pi = pair_i_.data() + kept;
    int* pk = pair_k_.data() + kept;
    double* pd = pair_d2_.data() + kept;
    int m = 0;
    if (uniform) {
      const double reach = max_radius_ + max_radius_ + margin, reach2 = reach * reach;
      for (int q = 0; q < n; ++q) {
        const int i = ci[q], k = ck[q];
        const double d2 = (Eigen::Map<const Point>(x + D * k) - Eigen::Map<const Point>(x + D * i)).squaredNorm();
        pi[m] = i, pk[m] = k, pd[m] = d2;
        m += d2 < reach2;
      }
    } else {
      for (int q = 0; q < n; ++q) {
        const int i = ci[q], k = ck[q];
        const double reach = radius[i] + radius[k] + margin;
        const double d2 = (Eigen::Map<const Point>(x + D * k) - Eigen::Map<const Point>(x + D * i)).squaredNorm();
        pi[m] = i, pk[m] = k, pd[m] = d2;
        m += d2 < reach * reach;
      }
    }
    kept += static_cast<size_t>(m);
  };
  for (int s = listed_; s < until;) {
    n = 0;
    for (; s < until && n < kBatch; ++s) {
      const int i = sorted[s];
      const int c = ball_cell_[i];
      list(i, s + 1, cell_start[c + 2]);
      for (int r = 0; r < kForwardRows<D>; ++r) {  // (a constant: the loop unrolls)
        const int m = c + forward_rows[r];
        list(i, cell_start[m - 1], cell_start[m + 2]);  // a row: three cells side by side
      }
    }
    keep_within_reach();
  }
  counters_.cell_queries += static_cast<long>(until - listed_) * (kForwardRows<D> + 1);
  listed_ = until;
  pair_count_ = static_cast<int>(kept);
  sort_by_gap(false);
}

// This file's members, for each dimension the class is instantiated for (ball_collisions.cpp).
#define MOTUS_NEIGHBOUR_LISTS(D) \
  template double BallCollisions<D>::fastest_slow_speed(double); \
  template bool BallCollisions<D>::lists_hold() const; \
  template void BallCollisions<D>::build_lists(double); \
  template void BallCollisions<D>::sort_by_gap(bool); \
  template void BallCollisions<D>::build_grid(); \
  template void BallCollisions<D>::list_pairs(int);
MOTUS_NEIGHBOUR_LISTS(1)
MOTUS_NEIGHBOUR_LISTS(2)
MOTUS_NEIGHBOUR_LISTS(3)
#undef MOTUS_NEIGHBOUR_LISTS

}  // namespace motus
