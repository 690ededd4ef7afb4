// The event-driven drift (ball_collisions.hpp): a step's contacts found, sorted by time and resolved one
// by one, and what a contact changes. The neighbour lists, the start's overlap, the fast balls, the walls
// and the contacts' rules are in the files beside it (neighbour_lists.cpp, start_overlaps.cpp,
// fast_balls.cpp, wall_contacts.cpp, collision_rules.cpp).
#include "motus/collide/ball_collisions.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "motus/collide/ball_collisions_tuning.hpp"
#include "motus/collide/sort_by_time.hpp"
#include "motus/collide/time_of_impact.hpp"
#include "motus/collide/too_many_collisions.hpp"
#include "motus/message_number.hpp"

namespace motus {

using namespace ball_collisions_tuning;

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

template class BallCollisions<1>;
template class BallCollisions<2>;
template class BallCollisions<3>;

}  // namespace motus
