#include "motus/collide/ball_collisions.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "motus/collide/impulse.hpp"
#include "motus/collide/sort_by_time.hpp"
#include "motus/collide/time_of_impact.hpp"
#include "motus/message_number.hpp"
#include "motus/collide/too_many_collisions.hpp"

namespace motus {
namespace {

// After this many collisions in one step, a ball's inelastic contacts (e < 1) become
// perfectly inelastic (e = 0): it stops the endless chatter of "inelastic collapse" (a
// ball trapped between two others losing a fraction of its speed at every touch)
// without touching elastic scenes.
constexpr unsigned kCollapseLimit = 64;

// A cluster settled at once (settle_cluster) has at most this many balls (the rest of a big
// pile is left to the events), and is settled when no contact approaches faster than this
// fraction of its fastest speed.
constexpr size_t kClusterBalls = 128;
constexpr double kSettled = 1e-14;
// The clusters' work in a step (contact_cluster.hpp's units, a contact's update each) is at most
// this many times the events' limit: a heap of thousands of balls with little restitution under
// gravity is more than clusters of 128 can settle, and without a bound its clusters took millions
// of sweeps each (a run that had failed at the events' limit went on for minutes). Once it is
// spent, the contacts go one at a time, perfectly inelastic, as before. (The bouncing balls with
// every e = 0.3 took at most 106,000 in a step: 41 times their limit of 2,600 events.)
constexpr long kClusterWorkPerEvent = 200;

// The rows of grid cells (three cells side by side along x) that a ball's pairs are listed from,
// besides its own: the forward half of the 3^(D−1) rows around it (build_grid), 1 in 2-D, 4 in 3-D.
template <int D>
constexpr int kForwardRows = ([] {
  int rows = 1;
  for (int k = 1; k < D; ++k) rows *= 3;
  return (rows - 1) / 2;
})();

// Overlap smaller than this fraction of the contact distance is rounding, not overlap.
constexpr double kOverlapSlack = kRoundingOverlap;  // (time_of_impact.hpp: the same rounding)
// Bodies whose gap is at most this fraction of their contact distance touch, for a plug-in's
// time of impact (its rounding and the engine's differ by a few units in the last place).
constexpr double kTouching = 1e-9;
// How far from touching a plug-in's time of impact may leave two bodies, as a fraction of their
// contact distance, plus the rounding of their positions' size: a root computed in any sensible
// way (a quadratic's, with its cancellation) is far closer; a wrong one (the radius left out, the
// later root) is off by the radius or more.
constexpr double kAtContact = 1e-6;
constexpr double kPositionRounding = 1e-12;

// Up to this many grid cells (half a megabyte of starts: in L2) the grid is counting-sorted
// in one level; beyond it, in two (see build_grid).
constexpr int kSmallGrid = 1 << 17;

// From this many bodies on (their x and v alone fill most of a 1 MB L2 cache), the passes
// that jump around — the listed pairs, and the events — fetch what they will need from
// memory ahead of time. Below it everything is in cache and a prefetch only costs.
constexpr int kPrefetchFrom = 1 << 14;
// The listed pairs' balls are fetched this many pairs ahead (about one memory latency ahead):
// a pair's second ball may be a row (in 3-D a plane) of balls away from its first.
constexpr int kPairPrefetch = 32;

// Building the lists goes through the grid's candidates this many at a time (a few kB: in L1),
// copying each range of balls kWindow at a time (a longer range is copied one by one); each
// step tests the listed pairs this many at a time.
constexpr int kBatch = 256;
constexpr int kWindow = 4;

// The lists' skin covers about this many steps of the fastest slow ball: a wider skin lists
// more pairs to test every step, a narrower one builds the lists more often. (Eight was the
// fastest in bench_collisions' gases, 2-D and 3-D, from 10^3 to 10^6 balls; four and sixteen
// were slower at every size.) It is at most the largest radius, unless a slow ball moves farther
// than half of that in one step: a skin of twice the step's sweep holds for that step.
constexpr double kSkinSteps = 8;

// A build sorts the pairs of each of the pair pass's batches into this many classes by their
// gap then (0 to skin, in equal parts): a pair whose balls were a gap g apart cannot touch
// until they have closed it, so a step tests only the classes the balls can have closed by its
// end — the nearest on the lists' first step, all of them on their last (about two thirds of
// the pairs over the lists' life).
constexpr int kGapClasses = 4;

// A correction of a ball's position larger than this fraction of the grid's cell takes the
// ball off the lists (it may now be near balls that are not on them); smaller ones (rounding)
// count against the lists' half skin, as the distance the ball moved.
constexpr double kNudge = 1e-9;

// The start's settling (settle_overlaps) sweeps the walls and the pairs at most this many times, and
// makes at most about this many tests (of a pair, or of a body and a wall, and a build of the lists
// as kSettleBuildWork a body) in all: a start with room for its balls is apart long before
// (measured: three balls of r = 0.5 m in a row 0.1 m into each other, pushed into a wall, in 92
// sweeps; a row of 20 in 4,239; 400 balls on a square lattice 0.1 m into each other, in a corner
// of their box, in 9,919, 0.15 s), one without room would go on for ever (six in a box 5 m wide:
// stopped by the sweeps, in 15 ms; 2,500 on a lattice of 0.79 m in a box of 40 m, by the tests,
// in 0.5 s). What is left the steps remove, a step at a time, as before.
constexpr int kSettleSweeps = 100'000;
constexpr long kSettleWork = 50'000'000;
constexpr long kSettleBuildWork = 10;  // (a build of the lists, in tests a body: it looks into its cells)

// A ball that moves more than this many radii in a step crosses others, and a gas of them needs
// many contacts a step: that, not overlap, is the likelier cause of too many.
constexpr double kFastRadii = 4;

// With this many fast balls or more at a step's start, they find each other in a grid of their
// paths (path_grid.hpp) rather than each testing all the others.
constexpr size_t kPathGridFrom = 32;
// The grid of paths cuts the time a typical fast ball's path lasts (to its first wall contact,
// or the step's end) into at most this many slabs: one a diameter of the path.
constexpr double kPathSlabs = 8;
// When stale entries (paths that contacts have changed since) make the grid of paths this
// many times as big as when it was last entered whole, it is entered whole again, from now.
constexpr size_t kPathGridGrowth = 4;

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
BallCollisions<D>::BallCollisions(const Vector& inverse_mass, std::vector<double> radius,
                                  std::vector<double> restitution, const Colliders& colliders,
                                  const ExternalCollisionRules* rules)
    : n_(static_cast<int>(inverse_mass.size())), rules_(rules), inverse_mass_(inverse_mass), radius_(std::move(radius)),
      restitution_(std::move(restitution)) {
  for (int i = 0; i < n_; ++i) {
    if (i > 0 && radius_[i] != radius_[0]) uniform_radius_ = false;
    if (i > 0 && inverse_mass_[i] != inverse_mass_[0]) uniform_inverse_mass_ = false;
    if (i > 0 && restitution_[i] != restitution_[0]) uniform_restitution_ = false;
    max_radius_ = std::max(max_radius_, radius_[i]);
    if (radius_[i] > 0) {
      balls_.push_back(i);
    } else {
      points_.push_back(i);
    }
  }
  for (const auto& p : colliders.planes) {
    Point n;
    for (int k = 0; k < D; ++k) n[k] = p.normal[k];
    const double length = n.norm();
    planes_.push_back({n / length, p.offset / length, p.restitution, -1, 0});
  }
  // A container: one inward-facing plane per face (after the general planes: build_lists
  // looks at the faces alone).
  for (const auto& b : colliders.boxes)
    for (int k = 0; k < D; ++k) {
      Point n = Point::Zero();
      n[k] = 1;
      planes_.push_back({n, b.min[k], b.restitution, k, 1});
      planes_.push_back({-n, -b.max[k], b.restitution, k, -1});
    }
  if constexpr (D == 2) {
    for (const auto& s : colliders.segments) segments_.push_back({{s.a[0], s.a[1]}, {s.b[0], s.b[1]}, s.restitution});
  } else if (!colliders.segments.empty()) {
    throw std::invalid_argument("segment colliders exist in 2-D scenes only");
  }
  state_.assign(static_cast<size_t>(n_), BallState{});
  ball_cell_.assign(n_, 0);
}

template <int D>
void BallCollisions<D>::advance(int i, double t) {
  // From where it is to t: back, if no contact has touched it yet (it is at the step's end).
  const double dt = t - h_ + state_[i].lag;
  if (dt == 0) return;
  position(i) += velocity(i) * dt;
  const bool untouched = state_[i].collisions_this_step == 0;
  state_[i].travelled = untouched ? velocity(i).norm() * t : state_[i].travelled + velocity(i).norm() * dt;
  state_[i].lag = h_ - t;
}

template <int D>
void BallCollisions<D>::drift(VectorRef x, VectorRef v, double h, bool kicked) {
  x_ = x.data();
  v_ = v.data();
  h_ = h;
  events_.clear();
  initial_events_.clear();
  events_this_step_ = 0;

  // A ball that may move farther than the largest radius in this step is fast. The others
  // move at most sweep_ (until a contact speeds one up: then it turns fast for the rest of the step).
  // Unless something but the last drift has changed the velocities (or the arrays, or the step),
  // the speeds the contacts left are known: every ball a contact made fast has left the lists,
  // and the bound on the others holds. Otherwise, and before a build, a look at every velocity.
  const bool speeds_known = !kicked && speeds_v_ == v_ && speeds_h_ == h;
  sweep_ = slow_speed_bound_ * h;
  if (!speeds_known || !lists_hold()) {
    slow_speed_bound_ = fastest_slow_speed(h);
    speeds_v_ = v_, speeds_h_ = h;
    sweep_ = slow_speed_bound_ * h;
  }
  // Balls that left the lists since they were built are fast every step until the next build.
  if (lists_hold()) {
    for (int i : fast_) make_fast(i);
    for (int i : escaped_)
      if (!state_[i].fast) state_[i].fast = true, fast_.push_back(i);
  } else if (!lists_built_ || lists_x_ != x_) {
    build_lists_at_start();  // (the scene's start, or positions the lists have never seen)
  } else {
    build_lists();
  }
  initial_search_ = true;
  find_initial_events();
  initial_search_ = false;
  sort_by_time(initial_events_, h, by_slice_, slice_start_);

  const long limit = 1000 + 100 * static_cast<long>(n_);
  cluster_budget_ = kClusterWorkPerEvent * limit;
  size_t next = 0;  // of initial_events_
  for (;;) {
    Event e;
    if (!events_.empty() && (next == initial_events_.size() || events_.front() < initial_events_[next])) {
      std::pop_heap(events_.begin(), events_.end(), std::greater<>());
      e = events_.back();
      events_.pop_back();
    } else if (next < initial_events_.size()) {
      e = initial_events_[next++];
      if (n_ >= kPrefetchFrom) fetch_ahead(next);
    } else {
      break;
    }
    if (state_[e.i].collisions_this_step != e.count_i) continue;  // stale: i has collided since
    if (e.other >= 0 && state_[e.other].collisions_this_step != e.count_other) continue;
    if (++events_this_step_ > limit) {
      // (With a plug-in, the contact that passed the limit says which of its times of impact to
      // look at: the contacts that never end are nearly all of one kind.)
      std::string why = "the scene cannot settle (overlapping bodies?)";
      // (Balls that cross many others in a step need that many contacts: then it is the speed.)
      double radii = 0;
      for (int b : balls_) radii = std::max(radii, velocity(b).norm() * h_ / radius_of(b));
      // (A ball pressed between others, or into a wall, by contacts that keep little of their
      // speed, is touched again and again at one instant, each contact leaving the next a little
      // less to do, without end: "inelastic collapse". The one with the most contacts says so.)
      int busiest = e.i;
      for (int b : balls_)
        if (state_[b].collisions_this_step > state_[busiest].collisions_this_step) busiest = b;
      if (state_[busiest].collisions_this_step >= kCollapseLimit)
        why = "body " + std::to_string(busiest) + " was touched " +
              std::to_string(state_[busiest].collisions_this_step) +
              " times in this step, pressed against others with little restitution: contacts taken one at a time "
              "at one instant cannot settle it (inelastic collapse); give the balls more restitution, or use "
              "--integrator verlet, which projects contacts";
      if (radii > kFastRadii)
        why = "the balls are too fast for the step (the fastest moves " + message_number(radii, 3) +
              " radii in one step of dt = " + message_number(h_, 3) + " s, crossing many others: a smaller dt?)";
      if (rules_ && e.other >= 0)
        why = "with the plug-in's times of impact and impulses, the contacts between balls never end (does its time "
              "of impact of two balls find a contact between balls that are moving apart?)";
      else if (rules_)
        why = "with the plug-in's times of impact and impulses, the contacts between a ball and a wall never end (does "
              "its time of impact with a plane find a contact for a ball moving away from the plane?)";
      throw TooManyCollisions("more than " + std::to_string(limit) + " collisions in one step: " + why);
    }
    resolve(e);
  }

  // Everybody to the end of the step: the pair pass moved every body there; those that
  // collided since go on from their last contact. Then clear what this step marked.
  const bool fetch = n_ >= kPrefetchFrom;
  const double limit2 = max_radius_ * max_radius_ / (h * h);
  double fastest2 = slow_speed_bound_ * slow_speed_bound_;
  for (size_t m = 0; m < moved_.size(); ++m) {
    if (const size_t ahead = m + 8; fetch && ahead < moved_.size()) {
      const int k = moved_[ahead];
      __builtin_prefetch(x_ + D * k);
      __builtin_prefetch(v_ + D * k);
      __builtin_prefetch(&state_[static_cast<size_t>(k)]);
    }
    const int i = moved_[m];
    position(i) += velocity(i) * state_[i].lag;
    state_[i].lag = 0;
    state_[i].travelled = 0;
    state_[i].collisions_this_step = 0;
    // Its speed now: a contact may have made it the fastest slow ball, or fast (off the lists).
    // (Points, radius 0, are not on the lists and do not count, as in fastest_slow_speed.)
    if (radius_of(i) <= 0) continue;
    const double speed2 = velocity(i).squaredNorm();
    if (speed2 <= limit2) {
      fastest2 = std::max(fastest2, speed2);
    } else if (!state_[i].escaped) {  // (a NaN speed too)
      state_[i].escaped = true;
      escaped_.push_back(i);
    }
  }
  slow_speed_bound_ = std::sqrt(fastest2);
  moved_.clear();
  for (int i : fast_) state_[i].fast = false;
  fast_.clear();
  fast_paths_on_ = false;
  // What the balls still on the lists may have moved: at most sweep_ each this step (faster
  // ones turned fast, and left them), and the small corrections.
  moved_since_build_ += sweep_ + nudged_;
  nudged_ = 0;
}

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
typename BallCollisions<D>::Cell BallCollisions<D>::cell_of(const Point& p) const {
  Cell c;
  for (int k = 0; k < D; ++k)
    // Clamped as a double before the conversion: a ball flung far outside the grid (or a
    // NaN, which std::max(1.0, NaN) turns into 1) must not overflow the int. Truncation,
    // not floor: the padding cell makes every coordinate ≥ 1, and std::floor is a library
    // call on baseline x86-64.
    c[k] = static_cast<int>(
        std::min(std::max(1.0, (p[k] - origin_[k]) * inverse_cell_size_), static_cast<double>(dims_[k] - 2)));
  return c;
}

template <int D>
int BallCollisions<D>::cell_index(const Cell& c) const {
  int index = 0;
  for (int k = 0; k < D; ++k) index += c[k] * stride_[k];
  return index;
}

template <int D>
template <class Visit>
void BallCollisions<D>::for_cells_in_box(const Point& low, const Point& high, Visit&& visit) {
  if (cell_start_.empty()) return;
  const Cell a = cell_of(low), b = cell_of(high);
  // Row by row: the cells of a row along x are consecutive, and so are their balls in
  // sorted_, so a row is one range (the same balls in the same order as cell by cell).
  const int row_cells = b[0] - a[0] + 1;
  Cell c = a;
  for (;;) {
    counters_.cell_queries += row_cells;
    const int first = cell_index(c);
    const int end = cell_start_[first + row_cells];
    for (int s = cell_start_[first]; s < end; ++s) visit(sorted_[s]);
    int k = 1;
    while (k < D && c[k] == b[k]) c[k] = a[k], ++k;  // an odometer over the rows of the box
    if (k >= D) break;
    ++c[k];
  }
}

template <int D>
void BallCollisions<D>::push(double t, int i, int other) {
  if (initial_search_) {  // (no body has collided yet this step: no need to look)
    initial_events_.push_back({t, i, other, 0, 0});
    return;
  }
  events_.push_back(
      {t, i, other, state_[i].collisions_this_step, other >= 0 ? state_[other].collisions_this_step : 0u});
  std::push_heap(events_.begin(), events_.end(), std::greater<>());
}

template <int D>
void BallCollisions<D>::fetch_ahead(size_t next) {
  // In three stages, each reading what the one before it fetched: the event 16 ahead fetches
  // its bodies (their data, lists' starts, masses and restitutions), 8 ahead their lists, 4
  // ahead their neighbours' data. By the time an event is resolved, its find_events finds all
  // of it in cache.
  for (int stage = 0; stage < 3; ++stage) {
    const size_t ahead = next + (size_t{16} >> stage) - 1;
    if (ahead < initial_events_.size()) prefetch_event(initial_events_[ahead], stage);
  }
}

template <int D>
void BallCollisions<D>::prefetch_event(const Event& e, int stage) {
  for (const int i : {e.i, e.other}) {
    if (i < 0) break;  // a wall
    const auto b = static_cast<size_t>(i);
    if (stage == 0) {
      __builtin_prefetch(&state_[b]);
      __builtin_prefetch(x_ + D * i);
      __builtin_prefetch(v_ + D * i);
      __builtin_prefetch(&neighbour_start_[b]);
      if (!uniform_inverse_mass_) __builtin_prefetch(&inverse_mass_[i]);  // (the impulse's)
      if (!uniform_restitution_) __builtin_prefetch(&restitution_[b]);
    } else if (stage == 1) {
      // (data() + start: the list may be empty, or end at this ball's start — &neighbours_[that] was
      // undefined behaviour, a reference through null or past the end; found by UBSan.)
      __builtin_prefetch(neighbours_.data() + neighbour_start_[b]);
    } else {
      for (int u = neighbour_start_[b], end = neighbour_start_[b + 1]; u < end; ++u) {
        const int k = neighbours_[static_cast<size_t>(u)];
        __builtin_prefetch(&state_[static_cast<size_t>(k)]);
        __builtin_prefetch(x_ + D * k);
        __builtin_prefetch(v_ + D * k);
      }
    }
  }
}

template <int D>
void BallCollisions<D>::separate(int i, int k) {
  const auto [by_i, by_k] = push_apart(i, k);
  moved_apart(i, by_i);
  moved_apart(k, by_k);
}

template <int D>
std::array<double, 2> BallCollisions<D>::push_apart(int i, int k) {
  const double w = inverse_mass_of(i) + inverse_mass_of(k);
  if (w == 0) return {0, 0};
  const Point d = position(k) - position(i);
  const double distance = d.norm();
  Point n = Point::Zero();
  if (distance > 0) {
    n = d / distance;
  } else {
    n[0] = 1;  // coincident centres: any direction will do
  }
  const double depth = radius_of(i) + radius_of(k) - distance;
  position(i) -= (depth * inverse_mass_of(i) / w) * n;
  position(k) += (depth * inverse_mass_of(k) / w) * n;
  ++counters_.position_corrections;
  return {depth * inverse_mass_of(i) / w, depth * inverse_mass_of(k) / w};
}

template <int D>
void BallCollisions<D>::moved_apart(int i, double distance) {
  if (radius_of(i) <= 0) return;  // (a point is on no list)
  if (distance > kNudge * cell_size_) {
    make_fast(i);  // it may now be near balls that are not on its list
  } else {
    nudged_ += distance;
  }
}

template <int D>
void BallCollisions<D>::make_fast(int i) {
  if (!state_[i].fast) state_[i].fast = true, fast_.push_back(i);
  if (!state_[i].escaped) state_[i].escaped = true, escaped_.push_back(i);
}

template <int D>
void BallCollisions<D>::test_pair(int i, int k, double t) {
  ++counters_.pair_tests;
  const Point dp = position_at(k, t) - position_at(i, t);
  const Point dv = velocity(k) - velocity(i);
  const double R = radius_of(i) + radius_of(k), dp_dp = dp.squaredNorm();
  const double toi = rules_ ? outside_balls_impact(position_at(i, t), velocity(i), radius_of(i), position_at(k, t),
                                                   velocity(k), radius_of(k), h_ - t)
                     : far_apart(dp_dp, R) ? far_sphere_sphere_impact(dp, dv, R, h_ - t)
                                           : sphere_sphere_impact(dp_dp, dp.dot(dv), dv.squaredNorm(), R, h_ - t);
  if (toi != kNoImpact) push(t + toi, i, k);
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

template <int D>
void BallCollisions<D>::find_initial_events() {
  // Walls, at the start of the step (every body at local time 0). Bodies outside the
  // lists (points, fast balls) and every general plane or segment: body by body. The
  // faces of box containers: only for the balls listed near them.
  const bool lists = balls_.size() >= 2;
  const bool general_walls =
      !segments_.empty() || std::any_of(planes_.begin(), planes_.end(), [](const Plane& p) { return p.axis < 0; });
  auto walls_one_by_one = [&](int i, bool faces_too) {
    for (size_t w = 0; w < planes_.size(); ++w)
      if (faces_too || planes_[w].axis < 0) initial_plane_event(i, static_cast<int>(w));
    for (size_t g = 0; g < segments_.size(); ++g) {
      separate_from_walls(i);
      const double toi = segment_impact(segments_[g], position(i), velocity(i), radius_of(i), h_, nullptr);
      if (toi != kNoImpact) push(toi, i, -1 - static_cast<int>(planes_.size() + g));
    }
  };
  for (size_t a = 0; a < fast_.size(); ++a) separate_from_walls(fast_[a]);  // their events come with find_events below
  if (!lists || general_walls) {
    for (int i : balls_)
      if (!state_[i].fast) walls_one_by_one(i, !lists);
  }
  for (int i : points_) walls_one_by_one(i, true);
  if (lists) {
    // (Box faces only, each along an axis. Most of these balls do not reach their face in this
    // step: that is told here with two multiplications, before the call that finds the time.
    // A ball a hair inside its face, or a NaN, goes on to the call, which decides as before.)
    const Plane* planes = planes_.data();
    const bool any_fast = !fast_.empty();
    for (const auto& [i, w] : near_faces_) {
      const Plane& face = planes[w];
      const double gap = plane_gap(face, position(i), radius_of(i));
      if (!(gap < 0) && gap + plane_closing(face, velocity(i)) * h_ > 0) continue;  // does not reach it this step
      if (!(any_fast && state_[i].fast)) initial_plane_event(i, w);
    }
  }

  // The listed pairs, a batch at a time in two passes, so that no branch depends on the balls
  // but rare ones:
  //   1. test every pair with sphere_sphere_impact's early "no" (not approaching, or still
  //      apart when the step ends), computed without a branch: the few left are the pairs that
  //      may touch within the step, and those that overlap;
  //   2. those get the exact time of impact and their events.
  // Overlapping balls are moved apart first (rare); then the rest of the batch is tested again
  // from where they now are.
  const double* x = x_;  // local copies: the compiler need not reload them after a push
  const double* v = v_;
  const double* radius = radius_.data();
  const bool uniform = uniform_radius_;
  const bool early_no = rules_ == nullptr;  // (a plug-in's time of impact decides every approaching pair)
  const double h = h_;
  const int* ci = pair_i_.data();
  const int* ck = pair_k_.data();
  const int pairs = pair_count_;
  const bool prefetch = n_ >= kPrefetchFrom;
  if (hits_.size() < static_cast<size_t>(kBatch)) hits_.resize(kBatch);
  int* hits = hits_.data();
  // Pass 1 over pairs [from, to): those left for pass 2, in order. The pairs tested after them
  // start at `next` (the next batch's): the pairs are known ahead, and their balls fetched ahead.
  // (Compiled twice, with and without the fetches: below kPrefetchFrom even the test for them costs.)
  auto filter = [&](int from, int to, int next, auto fetching) {
    int left = 0;
    for (int q = from; q < to; ++q) {
      if constexpr (fetching) {
        const int ahead = q + kPairPrefetch < to ? q + kPairPrefetch : q + kPairPrefetch - to + next;
        if (ahead < pairs) {
          for (const int b : {ci[ahead], ck[ahead]}) {
            __builtin_prefetch(x + D * b), __builtin_prefetch(v + D * b);
            // (and the other end in 3-D, where a ball's 24 bytes straddle two cache lines three times
            // in eight. In 2-D its 16 bytes are in one line when the array is 16-byte aligned, as an
            // Eigen vector's storage is; a Ref to an odd offset would only lose a prefetch in four.)
            if constexpr (D == 3) __builtin_prefetch(x + D * b + (D - 1)), __builtin_prefetch(v + D * b + (D - 1));
          }
        }
      }
      const int i = ci[q], k = ck[q];
      const Point dp = Eigen::Map<const Point>(x + D * k) - Eigen::Map<const Point>(x + D * i);
      const Point dv = Eigen::Map<const Point>(v + D * k) - Eigen::Map<const Point>(v + D * i);
      const double R = uniform ? max_radius_ + max_radius_ : radius[i] + radius[k];  // (radius_of, kept in registers)
      const double dp_dp = dp.squaredNorm(), dp_dv = dp.dot(dv), dv_dv = dv.squaredNorm();
      const bool overlap = dp_dp < R * R * (1 - kOverlapSlack);
      const bool still_closing = dp_dv + dv_dv * h <= 0;
      const bool apart_at_end = dp_dp - R * R + h * (2 * dp_dv + dv_dv * h) > 0;
      // (& and |, not && and ||: both sides are cheap, and a branch here is what this avoids)
      const bool no = (dp_dv >= 0) | (early_no & still_closing & apart_at_end);
      hits[left] = q;
      left += overlap | !no;
    }
    return left;
  };
  auto exact = [&](int q) {  // pass 2 for pair q; true when it moved the balls apart
    const int i = ci[q], k = ck[q];
    const double R = radius_of(i) + radius_of(k);
    Point dp = position(k) - position(i);
    double dp_dp = dp.squaredNorm();
    const bool moved = dp_dp < R * R * (1 - kOverlapSlack);
    if (moved) {
      separate(i, k);
      dp = position(k) - position(i);
      dp_dp = dp.squaredNorm();
    }
    const Point dv = velocity(k) - velocity(i);
    const double dp_dv = dp.dot(dv);
    if (dp_dv < 0) {
      const double toi = rules_ ? outside_balls_impact(position(i), velocity(i), radius_of(i), position(k), velocity(k),
                                                       radius_of(k), h)
                                : sphere_sphere_impact(dp_dp, dp_dv, dv.squaredNorm(), R, h);
      if (toi != kNoImpact) push(toi, i, k);
    }
    return moved;
  };
  // The gap classes the balls can have closed by the end of this step: each ball still on the
  // lists has moved at most moved_since_build_ + sweep_ (and this step's small corrections),
  // so the two of a pair together twice that. (Rounding in the gaps: the nudge's margin. With a
  // plug-in's rules, every listed pair: its time of impact is asked of all of them.)
  const double closed = 2 * (moved_since_build_ + sweep_ + nudged_) + 4 * kNudge * cell_size_;
  const double class_width = skin_ / kGapClasses;
  const int classes = rules_ || !(class_width > 0)
                          ? kGapClasses
                          : static_cast<int>(std::min<double>(kGapClasses, std::floor(closed / class_width) + 1));
  // Every body goes to the end of the step as soon as no pair left has it (frontier_): while
  // the pass is over its neighbourhood, in cache, rather than in a pass of its own over every
  // body after the events. The bodies go in ranges of their numbers (vectorised); in a gas
  // whose numbers follow space (a lattice's) the frontier lags the pass by a row of balls
  // (in 3-D a plane).
  const int* frontier = frontier_.data();
  int advanced = 0;  // bodies [0, advanced) are at the step's end
  auto advance_to = [&](int until) {
    if (until <= advanced) return;
    Eigen::Map<Eigen::VectorXd>(x_ + D * advanced, D * (until - advanced)) +=
        h * Eigen::Map<const Eigen::VectorXd>(v + D * advanced, D * (until - advanced));
    advanced = until;
  };
  long tested = 0;
  for (int batch = 0; batch < pairs; batch += kBatch) {
    const int end = class_start_[static_cast<size_t>(batch / kBatch) * (kGapClasses + 1) + classes];
    tested += end - batch;
    for (int from = batch; from < end;) {
      const int left = prefetch ? filter(from, end, batch + kBatch, std::true_type{})
                                : filter(from, end, batch + kBatch, std::false_type{});
      from = end;
      for (int j = 0; j < left; ++j)
        if (exact(hits[j])) {
          from = hits[j] + 1;
          break;
        }
    }
    advance_to(frontier[batch / kBatch + 1]);
  }
  advance_to(n_);
  counters_.pair_tests += tested;
  // Fast balls look along their whole path (and at each other). (A ball moved apart above
  // turned fast and joined them.)
  // (Their walls first: the first wall contact ends the path each enters in the grid of paths.)
  for (size_t a = 0; a < fast_.size(); ++a) find_wall_events(fast_[a], 0);
  start_fast_paths();
  for (size_t a = 0; a < fast_.size(); ++a) find_ball_events(fast_[a], 0, -1);
}

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
void BallCollisions<D>::find_events(int i, double t, int exclude) {
  find_wall_events(i, t);
  find_ball_events(i, t, exclude);
}

template <int D>
void BallCollisions<D>::find_ball_events(int i, double t, int exclude) {
  // (After find_wall_events(i, t): its horizon.)
  if (radius_of(i) <= 0 || balls_.size() < 2) return;
  if (!state_[i].fast) {
    // Its possible partners are on its list, or are fast.
    for (int u = neighbour_start_[i], end = neighbour_start_[i + 1]; u < end; ++u) {
      const int k = neighbours_[u];
      if (k != exclude && !state_[k].fast) test_pair(i, k, t);
    }
  } else {
    // A fast ball's partners are anywhere near its remaining path (up to its horizon): within
    // half the skin of where the grid has them.
    const Point p = position_at(i, t), q = p + velocity(i) * (state_[i].horizon - t);
    const double margin = radius_of(i) + max_radius_ + 0.5 * skin_ + kNudge * cell_size_;
    for_cells_in_box(p.cwiseMin(q).array() - margin, p.cwiseMax(q).array() + margin, [&](int k) {
      if (k != i && k != exclude && !state_[k].fast) test_pair(i, k, t);
    });
  }
  for_fast_near(i, t, [&](int k) {
    if (k != i && k != exclude) test_pair(i, k, t);
  });
}

template <int D>
template <class Visit>
void BallCollisions<D>::for_fast_near(int i, double t, Visit&& visit) {
  // The fast balls ball i may meet from t to the step's end: every one, or those whose paths
  // pass near its own in their grid.
  if (fast_paths_on_) {
    const Point p = position_at(i, t);
    const long cells = fast_paths_.for_near(
        p, velocity(i), t, state_[i].horizon, path_margin(i, p),
        [this](int k) { return state_[k].collisions_this_step; }, visit);
    if (cells >= 0) {
      counters_.cell_queries += cells;
      return;
    }
  }
  for (int k : fast_) visit(k);
}

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

template <int D>
void BallCollisions<D>::mark_fast_if_needed(int i, double t) {
  if (state_[i].fast || radius_of(i) <= 0) return;
  if (state_[i].travelled + velocity(i).norm() * (h_ - t) > sweep_) make_fast(i);  // (and off the lists)
}

template <int D>
void BallCollisions<D>::resolve(const Event& e) {
  const int i = e.i;
  // A ball in inelastic collapse: it and the balls that touch it are settled at once (below).
  // (Not with a plug-in's impulses: their contacts are the student's, one at a time.)
  if ((state_[i].collisions_this_step >= kCollapseLimit ||
       (e.other >= 0 && state_[e.other].collisions_this_step >= kCollapseLimit)) &&
      !rules_ && cluster_budget_ > 0 &&
      restitution_of(i) * (e.other >= 0 ? restitution_of(e.other) : wall_restitution(-1 - e.other)) < 1) {
    settle_cluster(e);
    return;
  }
  if (state_[i].collisions_this_step == 0) moved_.push_back(i);
  advance(i, e.t);
  if (e.other >= 0) {
    const int k = e.other;
    if (state_[k].collisions_this_step == 0) moved_.push_back(k);
    advance(k, e.t);
    const Point d = position(k) - position(i);
    const double distance = d.norm();
    if (distance > 0) {
      double restitution = restitution_of(i) * restitution_of(k);
      if (restitution < 1 &&
          (state_[i].collisions_this_step >= kCollapseLimit || state_[k].collisions_this_step >= kCollapseLimit))
        restitution = 0;
      collide(i, k, Point(d / distance), restitution);
    }
    ++state_[i].collisions_this_step;
    ++state_[k].collisions_this_step;
    ++counters_.ball_collisions;
    mark_fast_if_needed(i, e.t);
    mark_fast_if_needed(k, e.t);
    // (Walls first: their first contacts end the new paths.)
    find_wall_events(i, e.t);
    find_wall_events(k, e.t);
    if (fast_paths_on_) enter_fast_paths(i, k, e.t);
    find_ball_events(i, e.t, k);
    find_ball_events(k, e.t, i);
  } else {
    const int w = -1 - e.other;
    double restitution = restitution_of(i) * wall_restitution(w);
    if (restitution < 1 && state_[i].collisions_this_step >= kCollapseLimit) restitution = 0;
    bounce(i, wall_normal(i, w), restitution);
    ++state_[i].collisions_this_step;
    ++counters_.wall_collisions;
    mark_fast_if_needed(i, e.t);
    find_wall_events(i, e.t);
    if (fast_paths_on_) enter_fast_paths(i, -1, e.t);
    find_ball_events(i, e.t, -1);
  }
}

template <int D>
double BallCollisions<D>::wall_restitution(int wall) const {
  return wall < static_cast<int>(planes_.size()) ? planes_[static_cast<size_t>(wall)].restitution
                                                 : segments_[static_cast<size_t>(wall) - planes_.size()].restitution;
}

// Inelastic collapse (contact_cluster.hpp): once a ball has had kCollapseLimit contacts in a step,
// its next contact with little restitution settles it together with every ball that touches it,
// or touches one of them, through such contacts (and the walls they touch), now, at once and
// perfectly inelastically — as its contacts one at a time would have, in the limit (they were
// already perfectly inelastic from that many on). Elastic contacts (e = 1) stay the events'.
template <int D>
void BallCollisions<D>::settle_cluster(const Event& e) {
  const double t = e.t;
  cluster_.clear();
  cluster_balls_.clear();
  auto join = [&](int k) {  // (at t, like every body a contact moves)
    if (state_[k].collisions_this_step == 0) moved_.push_back(k);
    advance(k, t);
    cluster_balls_.push_back(k);
    return cluster_.add_body(velocity(k), inverse_mass_of(k));
  };
  auto member = [&](int k) {  // its place in the cluster, or −1
    const auto at = std::find(cluster_balls_.begin(), cluster_balls_.end(), k);
    return at == cluster_balls_.end() ? -1 : static_cast<int>(at - cluster_balls_.begin());
  };
  join(e.i);
  if (e.other >= 0) join(e.other);
  const int walls = static_cast<int>(planes_.size() + segments_.size());
  for (int m = 0; m < static_cast<int>(cluster_balls_.size()); ++m) {
    const int b = cluster_balls_[static_cast<size_t>(m)];
    const double r = radius_of(b);
    const Point p = position(b);
    for (int w = 0; w < walls; ++w) {
      if (restitution_of(b) * wall_restitution(w) >= 1) continue;
      const double gap = w < static_cast<int>(planes_.size())
                             ? planes_[static_cast<size_t>(w)].normal.dot(p) - planes_[static_cast<size_t>(w)].offset - r
                             : (p - nearest_on(segments_[static_cast<size_t>(w) - planes_.size()], p)).norm() - r;
      if (gap <= kTouching * std::max(r, 1e-300)) cluster_.add_contact(-1, m, wall_normal(b, w));
    }
    if (r <= 0 || balls_.size() < 2) continue;
    auto consider = [&](int k) {
      if (k == b || radius_of(k) <= 0 || restitution_of(b) * restitution_of(k) >= 1) return;
      const double R = r + radius_of(k);
      const Point d = position_at(k, t) - p;
      const double distance = d.norm();
      if (!(distance - R <= kTouching * R) || distance == 0) return;
      int j = member(k);
      if (j >= 0 && (j < m || cluster_.has_contact(m, j))) return;  // (given when k was taken, or just now)
      if (j < 0) {
        if (cluster_balls_.size() >= kClusterBalls) return;  // (left to the events)
        j = join(k);
      }
      cluster_.add_contact(m, j, d / distance);
    };
    // Its neighbours: on its list, or (a fast ball's) near it in the grid; and the fast balls.
    if (!state_[b].fast) {
      for (int u = neighbour_start_[b], end = neighbour_start_[b + 1]; u < end; ++u)
        if (!state_[neighbours_[u]].fast) consider(neighbours_[u]);
    } else {
      const double margin = r + max_radius_ + 0.5 * skin_ + kNudge * cell_size_;
      for_cells_in_box(p.array() - margin, p.array() + margin, [&](int k) {
        if (!state_[k].fast) consider(k);
      });
    }
    for_fast_near(b, t, consider);
  }
  double scale = 0;  // (the speeds', for when a contact is at rest)
  for (int j = 0; j < cluster_.bodies(); ++j) scale = std::max(scale, cluster_.velocity(j).norm());
  cluster_.settle(kSettled * scale, cluster_budget_);  // (if not quite, what is left is the events')

  for (int j = 0; j < cluster_.bodies(); ++j) {
    const int b = cluster_balls_[static_cast<size_t>(j)];
    velocity(b) = cluster_.velocity(j);
    ++state_[b].collisions_this_step;
  }
  for (int c = 0; c < cluster_.contacts(); ++c)
    if (cluster_.impulse(c) > 0) ++(cluster_.wall_side(c) < 0 ? counters_.wall_collisions : counters_.ball_collisions);
  for (int b : cluster_balls_) mark_fast_if_needed(b, t);
  for (int b : cluster_balls_) find_wall_events(b, t);  // (walls first: their first contacts end the new paths)
  if (fast_paths_on_)
    for (int b : cluster_balls_) enter_fast_paths(b, -1, t);
  for (int b : cluster_balls_) find_ball_events(b, t, -1);
}

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

template class BallCollisions<1>;
template class BallCollisions<2>;
template class BallCollisions<3>;

}  // namespace motus
