// The ball pairs' broad phase: a neighbour list, built by a spatial hash and kept across projections,
// and each projection's candidate pairs from it. Its own part: it runs once a projection, not in the sweeps.
#include "motus/constrain/constraint_projection.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace motus {
namespace {

// Cells of the ball pairs' hash are numbered within ±this along each axis (1e6 cells: over
// 100 km for the shipped ragdoll's balls), so that a neighbour's index, ±1, never overflows.
constexpr double kFarthestCell = 1e6;

// The classic spatial-hash primes (Teschner et al., "Optimized Spatial Hashing for
// Collision Detection of Deformable Objects", 2003).
std::uint64_t hash_cell(const std::array<std::int64_t, 3>& c) {
  return static_cast<std::uint64_t>(c[0]) * 73856093u ^ static_cast<std::uint64_t>(c[1]) * 19349663u ^
         static_cast<std::uint64_t>(c[2]) * 83492791u;
}

// |x_k − x_i|² for bodies i and k of a D-dimensional position vector.
template <int D>
inline double squared_distance(const double* x, int i, int k) {
  double distance2 = 0;
  for (int c = 0; c < D; ++c) {
    const double delta = x[D * k + c] - x[D * i + c];
    distance2 += delta * delta;
  }
  return distance2;
}

}  // namespace

// The broad phase, at the start of every projection: the candidate pairs are the pairs of balls
// closer than r_a + r_b + margin; the sweeps then test only those. The margin (the largest
// radius) covers the distance balls move relative to each other during the sweeps; the few pairs
// it would miss (balls thrown together by more than a radius within one projection) are found at
// the next step.
//
// Finding them is a neighbour ("Verlet") list kept across projections: the pairs closer than
// r_a + r_b + margin + skin at the list's build, reused as long as no ball has moved more than
// skin/2 since (one pass over the balls). Two balls that have each moved at most skin/2 have come
// at most a skin closer, so a pair closer than r_a + r_b + margin now was closer than
// r_a + r_b + margin + skin at the build: the candidates are exactly the ones a fresh search would
// find. ball_gas at 1/60 s builds the list about once in 23 steps, where a spatial hash built at
// every projection cost most of the step.
void ConstraintProjection::find_ball_pairs(ConstVectorRef x) {
  switch (d_) {
    case 1: find_ball_pairs_in<1>(x.data()); break;
    case 2: find_ball_pairs_in<2>(x.data()); break;
    default: find_ball_pairs_in<3>(x.data()); break;
  }
}

template <int D>
void ConstraintProjection::find_ball_pairs_in(const double* x) {
  if (!have_neighbours_ || !neighbours_still_hold<D>(x)) build_neighbours<D>(x);
  select_close_pairs<D>(x);
}

// Whether every ball is still within skin/2 of where it was at the build. (Written so that a NaN
// position, which compares false, builds again.)
template <int D>
bool ConstraintProjection::neighbours_still_hold(const double* x) const {
  const double limit2 = 0.25 * skin_ * skin_;
  const double* then = built_at_.data();
  for (const int i : balls_) {
    const double* now = x + D * i;
    double moved2 = 0;
    for (int k = 0; k < D; ++k) {
      const double step = now[k] - then[k];
      moved2 += step * step;
    }
    if (!(moved2 <= limit2)) return false;
    then += D;
  }
  return true;
}

// The neighbour list from scratch: hash every ball into a uniform grid of cells (a spatial hash,
// so the grid needs no bounds), then look for each ball's partners in its own and the
// neighbouring cells only — O(N) rather than all N²/2 pairs.
//
// The list is sorted by (i, k), the order of the Gauss–Seidel pushes: a push moves the balls the
// next pair reads, so the order decides the result's last bits. In the hash's order it would
// depend on which cells the balls were in at the build, and so on when the list was built; in
// (i, k) order a projection's result depends on its start positions alone — deterministic, and
// the same whether the list was built by this projection or ten steps ago. (The build visits
// the balls in index order already; each ball's partners, a handful, are sorted in place.)
template <int D>
void ConstraintProjection::build_neighbours(const double* x) {
  const double cell = 2 * max_radius_ + margin_ + skin_;  // the farthest a listed pair can be apart
  const auto buckets = static_cast<std::uint64_t>(bucket_start_.size() - 1);
  auto cell_of = [&](int i) {
    std::array<std::int64_t, 3> c{0, 0, 0};
    for (int k = 0; k < D; ++k) {
      // Clamped as a double before the cast (a cast of a double beyond int64's range, or of
      // NaN, is undefined behaviour): a ball flung farther than kFarthestCell cells shares the
      // edge cell with any other out there, which only makes them candidates the exact
      // distance test then looks at; NaN (a position no step should make) goes to cell 0.
      const double cell_index = std::floor(x[i * D + k] / cell);
      c[k] = std::isnan(cell_index) ? 0 : static_cast<std::int64_t>(std::clamp(cell_index, -kFarthestCell, kFarthestCell));
    }
    return c;
  };

  // Counting sort of the balls by bucket.
  std::fill(bucket_start_.begin(), bucket_start_.end(), 0);
  for (size_t s = 0; s < balls_.size(); ++s) {
    bucket_of_[s] = static_cast<int>(hash_cell(cell_of(balls_[s])) & (buckets - 1));
    ++bucket_start_[static_cast<size_t>(bucket_of_[s]) + 1];
  }
  for (size_t b = 0; b + 1 < bucket_start_.size(); ++b) bucket_start_[b + 1] += bucket_start_[b];
  for (size_t s = 0; s < balls_.size(); ++s) sorted_[static_cast<size_t>(bucket_start_[bucket_of_[s]]++)] = static_cast<int>(s);
  for (size_t b = bucket_start_.size() - 1; b > 0; --b) bucket_start_[b] = bucket_start_[b - 1];
  bucket_start_[0] = 0;

  neighbours_.clear();
  int neighbour_cells = 1;
  for (int k = 0; k < D; ++k) neighbour_cells *= 3;
  for (size_t s = 0; s < balls_.size(); ++s) {
    const int i = balls_[s];
    const size_t first = neighbours_.size();
    const auto home = cell_of(i);
    // Two neighbouring cells may hash to the same bucket: look into each bucket once.
    std::array<int, 27> seen{};
    int seen_count = 0;
    for (int code = 0; code < neighbour_cells; ++code) {
      auto c = home;
      for (int k = 0, rest = code; k < D; ++k, rest /= 3) c[k] += rest % 3 - 1;
      const int bucket = static_cast<int>(hash_cell(c) & (buckets - 1));
      if (std::find(seen.begin(), seen.begin() + seen_count, bucket) != seen.begin() + seen_count) continue;
      seen[static_cast<size_t>(seen_count++)] = bucket;
      ++broad_phase_queries_;
      for (int u = bucket_start_[bucket]; u < bucket_start_[bucket + 1]; ++u) {
        const auto other = static_cast<size_t>(sorted_[static_cast<size_t>(u)]);
        if (other <= s) continue;  // each pair once: from its earlier ball
        const int k = balls_[other];
        const double reach = radius_[i] + radius_[k] + margin_ + skin_;
        if (squared_distance<D>(x, i, k) < reach * reach) neighbours_.push_back({i, k});
      }
    }
    std::sort(neighbours_.begin() + static_cast<std::ptrdiff_t>(first), neighbours_.end());
    std::copy(x + D * i, x + D * (i + 1), built_at_.begin() + static_cast<std::ptrdiff_t>(D * s));
  }
  have_neighbours_ = true;
  ++ball_pair_builds_;
}

// The candidates of this projection: the neighbours closer than r_a + r_b + margin now (the set
// a search from scratch would find, in the list's order).
template <int D>
void ConstraintProjection::select_close_pairs(const double* x) {
  pairs_.clear();
  for (const auto& [i, k] : neighbours_) {
    const double reach = radius_[i] + radius_[k] + margin_;
    if (squared_distance<D>(x, i, k) < reach * reach) pairs_.push_back({i, k});
  }
}

}  // namespace motus
