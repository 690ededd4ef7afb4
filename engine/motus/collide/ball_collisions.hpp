#pragma once
// Bodies that touch: balls (and points) move on straight lines through a step, and every
// contact — ball with ball, ball with wall — is resolved at its own time of impact, in
// time order (an event-driven drift). Nothing tunnels, however fast, and contacts that
// happen at the same instant (Newton's cradle) are resolved one after another, exactly.
//
// One step, for time h, given the velocities the integrator's kick left:
//   1. find every contact that can happen within h. The candidates are the pairs of a
//      neighbour list (a "Verlet list", as in molecular dynamics): every two balls that were
//      closer than r_a + r_b + skin when the list was built. A ball that has moved less than
//      skin/2 since then cannot touch a ball off its list, so the list serves step after step
//      until the fastest ball may have used up that half skin (with no kick between steps,
//      only contacts change speeds: the fastest is known without reading every velocity);
//      then it is built again, from a uniform grid whose cells (2·r_max + skin) put every two
//      balls within reach in neighbouring cells (the broad phase: O(N), not O(N²)). Balls
//      that may have left their list's reach — fast ones, moving farther than a radius in one
//      step, and balls pushed apart — are "fast": they query the grid's cells along their path
//      until the next build, and find each other in a grid of their paths (path_grid.hpp),
//      not pair by pair (a gas of small quick balls is nearly all fast). As soon as no listed
//      pair left to test has a body, it is moved to the end of the step (a body no contact
//      touches needs nothing more: BallState::lag);
//   2. take the earliest contact, move its two bodies to that time, apply the impulse
//      (impulse.hpp), and look again for the contacts of just those two (their lists);
//   3. repeat until no contact is left within h; move the bodies that collided on to the end.
//      (A ball that has had 64 contacts in the step, pressed between others with little
//      restitution, is settled at once with every ball touching it: contact_cluster.hpp.)
// Overlap found at the start of a step (from the scene, or rounding) is removed by
// moving positions apart along the normal, mass-weighted; velocities are not touched.
// The scene's own overlap (at a drift's first build of the lists on its positions) is removed
// whole before that step: walls and listed pairs are swept in turn until nothing overlaps
// (settle_overlaps), for a pair moved apart may push a ball into a wall or into another ball.
// The lists assume that only this drift moves the bodies: a drift given other arrays
// builds them again.
//
// The parts, one file each: the event-driven drift itself (ball_collisions.cpp), the neighbour
// lists and their grid (neighbour_lists.cpp), the scene's overlap removed at the start
// (start_overlaps.cpp), the fast balls' searches along their paths (fast_balls.cpp), the walls
// (wall_contacts.cpp), the contacts' impulses and times of impact, the engine's or a plug-in's
// (collision_rules.cpp), and the numbers they are tuned with (ball_collisions_tuning.hpp).
#include <algorithm>  // (cell_of's clamp)
#include <array>
#include <vector>

#include "motus/collide/colliders.hpp"
#include "motus/collide/contact_cluster.hpp"
#include "motus/collide/path_grid.hpp"
#include "motus/external/external_parts.hpp"
#include "motus/huge_pages.hpp"
#include "motus/vector.hpp"

namespace motus {

struct CollisionCounters {
  long grid_builds = 0;           // broad phase: grids built
  long cell_queries = 0;          // broad phase: grid cells looked into
  long pair_tests = 0;            // narrow phase: time-of-impact computations between two balls
  long ball_collisions = 0;
  long wall_collisions = 0;
  long position_corrections = 0;  // overlaps removed by moving positions
  long path_grids = 0;            // steps whose fast balls looked for each other in a grid of their paths

  long broad_phase_queries() const { return grid_builds + cell_queries; }
};

template <int D>
class BallCollisions {
public:
  using Point = Eigen::Matrix<double, D, 1>;

  // radius 0 makes a point: it meets walls but not other bodies. `rules`, when given (a
  // plug-in's), replace the impulses and the times of impact of ball–ball and ball–plane
  // contacts (segments keep the engine's time of impact, and use the rules' wall bounce).
  BallCollisions(const Vector& inverse_mass, std::vector<double> radius, std::vector<double> restitution,
                 const Colliders& colliders, const ExternalCollisionRules* rules = nullptr);

  // Moves every body for time h on straight lines from x with velocities v, resolving
  // every contact at its time of impact. x and v hold N·D numbers. `kicked`: whether anything
  // but the last drift has changed v since (a kick; the first drift always looks at every
  // speed). When nothing has, only the contacts have changed speeds, and the step need not
  // read every ball's velocity to know how far the slow ones can go.
  void drift(VectorRef x, VectorRef v, double h, bool kicked = true);

  const CollisionCounters& counters() const { return counters_; }

private:
  struct Event {
    double t;
    int i, other;                   // other ≥ 0: a ball; other < 0: wall −1 − other
    unsigned count_i, count_other;  // the bodies' collisions this step when it was found: stale once either has more
    // Time order. Equal times go by the bodies, so that the order never depends on the
    // order the events were found in (or on the way they were stored).
    bool operator>(const Event& e) const {
      if (t != e.t) return t > e.t;
      if (i != e.i) return i > e.i;
      return other > e.other;
    }
    bool operator<(const Event& e) const { return e > *this; }
  };
  // The free side is normal·x ≥ offset. Box faces are axis-aligned (axis ≥ 0, normal
  // = sign·e_axis), which makes their test two multiplications.
  struct Plane {
    Point normal;
    double offset, restitution;
    int axis;
    double sign;
  };
  struct Segment {
    Point a, b;
    double restitution;
  };
  using Cell = std::array<int, D>;

  // (Most scenes' balls are all alike: then the event path reads no radius, mass or
  // restitution from memory — at 10^6 balls each would be one more cache miss per body.)
  double radius_of(int i) const { return uniform_radius_ ? max_radius_ : radius_[static_cast<size_t>(i)]; }
  double inverse_mass_of(int i) const { return uniform_inverse_mass_ ? inverse_mass_[0] : inverse_mass_[i]; }
  double restitution_of(int i) const {
    return uniform_restitution_ ? restitution_[0] : restitution_[static_cast<size_t>(i)];
  }
  auto position(int i) { return Eigen::Map<Point>(x_ + D * i); }
  auto velocity(int i) { return Eigen::Map<Point>(v_ + D * i); }
  // Where body i is at time t of the step (once the pair pass has moved it: see BallState::lag).
  Point position_at(int i, double t) { return position(i) + velocity(i) * (t - h_ + state_[i].lag); }
  void advance(int i, double t);

  void build_grid();
  [[gnu::always_inline]] inline Cell cell_of(const Point& p) const;  // (in every per-ball loop of the grid)
  inline int cell_index(const Cell& c) const;
  template <class Visit>
  void for_cells_in_box(const Point& low, const Point& high, Visit&& visit);

  // Calls f(i) for every slow ball, in balls_'s order. (Most steps have no fast ball: then
  // every ball is slow, without reading its flag.)
  template <class F>
  void for_slow(F&& f) const {
    if (fast_.empty()) {
      for (int i : balls_) f(i);
    } else {
      for (int i : balls_)
        if (!state_[i].fast) f(i);
    }
  }
  double fastest_slow_speed(double h);
  bool lists_hold() const;
  // (least_skin: the settling's lists, which must hold while the balls are pushed about.)
  void build_lists(double least_skin = 0);
  void build_lists_at_start();
  bool settle_overlaps();
  void list_pairs(int until);
  void sort_by_gap(bool last);
  void find_initial_events();
  void initial_plane_event(int i, int wall);
  void find_events(int i, double t, int exclude);
  void find_wall_events(int i, double t);
  void find_ball_events(int i, double t, int exclude);
  void test_pair(int i, int k, double t);
  void separate(int i, int k);
  void separate_from_walls(int i);
  // The moves alone (counted as position corrections): how far each body moved, 0 if not.
  std::array<double, 2> push_apart(int i, int k);
  double push_out_of_plane(int i, int wall);
  double push_off_segment(int i, const Segment& s);
  void moved_apart(int i, double distance);
  inline void make_fast(int i);
  double segment_impact(const Segment& s, const Point& p, const Point& u, double r, double horizon, Point* normal) const;
  static Point nearest_on(const Segment& s, const Point& p);  // the segment's point nearest p
  Point wall_normal(int i, int wall);
  // How far a ball of radius r at p is from the plane's surface (below 0: inside it), and how fast a
  // velocity u closes that gap: for a box face, along an axis, one multiplication each. Every wall
  // search and correction reads these two, so that they agree to the last bit.
  template <class P>
  static double plane_gap(const Plane& plane, const P& p, double r) {
    return (plane.axis >= 0 ? plane.sign * p[plane.axis] : plane.normal.dot(p)) - plane.offset - r;
  }
  template <class U>
  static double plane_closing(const Plane& plane, const U& u) {
    return plane.axis >= 0 ? plane.sign * u[plane.axis] : plane.normal.dot(u);
  }
  void push(double t, int i, int other);
  // (noipa: a prefetch is no side effect to GCC, which then finds the function pure and
  // drops the call.)
  [[gnu::noipa]] void fetch_ahead(size_t next);
  [[gnu::always_inline]] inline void prefetch_event(const Event& e, int stage);
  // The rules from outside, in the engine's terms (times relative to now, +∞ for none).
  double outside_balls_impact(const Point& p_a, const Point& v_a, double r_a, const Point& p_b, const Point& v_b,
                              double r_b, double horizon);
  double outside_plane_impact(const Point& p, const Point& v, double r, const Plane& plane, double horizon);
  void collide(int i, int k, const Point& n, double e);
  void bounce(int i, const Point& n, double e);
  void resolve(const Event& e);
  inline double wall_restitution(int wall) const;
  void settle_cluster(const Event& e);
  inline void mark_fast_if_needed(int i, double t);
  void start_fast_paths();
  void enter_fast_path(int i, double t);
  void enter_fast_paths(int i, int k, double t);
  double path_margin(int i, const Point& p) const;
  template <class Visit>
  void for_fast_near(int i, double t, Visit&& visit);

  int n_;
  const ExternalCollisionRules* rules_;
  Vector inverse_mass_;
  std::vector<double> radius_, restitution_;
  double max_radius_ = 0;
  bool uniform_radius_ = true;  // every body's radius is max_radius_
  bool uniform_inverse_mass_ = true, uniform_restitution_ = true;  // every body's is body 0's
  std::vector<Plane> planes_;
  std::vector<Segment> segments_;
  CollisionCounters counters_;

  // Per step (sized once; a step allocates nothing once they have grown).
  double* x_ = nullptr;
  double* v_ = nullptr;
  double h_ = 0;
  double sweep_ = 0;  // farthest any slow ball may travel in this step
  // What a contact reads and writes of a body besides x and v, side by side: one cache
  // line per body rather than one per array (at 10^6 balls each is a miss).
  struct BallState {
    // How long before the step's end the time of its x is. The pair pass moves the bodies to
    // the end of the step as soon as no pair is left to test with them (while their x and v
    // are still in cache: no pass of its own over every body), so a body no contact has
    // touched is at the end, lag 0; a contact moves its bodies back to its time. (Until the
    // pair pass has moved it, a body's x is at the step's start.)
    double lag = 0;
    double travelled = 0;  // since the step's start
    unsigned collisions_this_step = 0;  // events carry it to detect staleness
    // When its first wall contact is, as its last search found it (the step's end if none): no
    // contact of its later than that can happen — the wall's comes first, and changes its
    // velocity, and the later contacts' events are then stale — so its searches and its path
    // in the grid of paths end there. (A fast gas crosses its container many times in a step:
    // its lines through the whole step pass near every other ball.)
    double horizon = 0;
    bool fast = false;     // searches along its path this step (not by its list)
    bool escaped = false;  // off the lists until they are built again: fast every step
  };
  BigArray<BallState> state_;
  BigArray<int> balls_;
  std::vector<int> fast_, points_, moved_;
  // The contacts found at the start of a step (nearly all of a step's) are sorted once
  // (sort_by_time.hpp) and taken in order; those found after a contact go into a heap, and
  // the two are merged.
  // Known in advance, the next events' bodies are fetched from memory before they are
  // needed: at 10^6 balls each is a few cache misses, one after another.
  std::vector<Event> initial_events_, events_;
  std::vector<Event> by_slice_;  // (sort_by_time's buffers)
  std::vector<int> slice_start_;
  bool initial_search_ = false;  // pushes go to initial_events_
  long events_this_step_ = 0;

  // The grid of slow balls' start positions, counting-sorted by cell. It has one empty
  // cell of padding on every side, so a neighbour of a ball's cell is always a cell.
  Point origin_, grid_low_, grid_high_;
  double cell_size_ = 1, inverse_cell_size_ = 1;
  Cell dims_{}, stride_{};
  // (The arrays of one number or more per ball or cell are BigArrays: huge_pages.hpp.)
  BigArray<int> cell_start_, sorted_, ball_cell_;
  int slow_count_ = 0;  // the balls in the grid (sorted_ has padding after them)
  std::vector<int> candidate_i_, candidate_k_, hits_;  // the pair search's batch (find_initial_events)
  struct Placed {
    int ball, cell;
  };
  std::vector<int> block_start_, local_count_;  // the sort's first level, and its second's counts
  BigArray<Placed> by_block_;
  std::vector<int> forward_rows_;
  int max_forward_ = 0;  // the farthest forward row's offset

  // The fastest a slow ball can be now: exact after a look at every velocity, then raised by
  // each contact's new speeds (so never less than the truth) until the next look.
  double slow_speed_bound_ = 0;
  const double* speeds_v_ = nullptr;  // the velocities' array it was found on, and the step it took
  double speeds_h_ = 0;

  // The neighbour lists (see the top). Built from the grid, with the balls where they were
  // then; the grid is kept with them, for the fast balls' searches.
  double skin_ = 0;
  double moved_since_build_ = 0;  // the most any ball still on the lists may have moved since
  double nudged_ = 0;             // this step's position corrections too small to take a ball off
  bool lists_built_ = false;
  const double* lists_x_ = nullptr;  // the positions' array they were built on
  // Every pair of balls within reach, once, in the grid's order by batch of the pair pass
  // (kBatch), and within a batch by gap class: the batch's class c is [class_start_[b·(K+1) + c],
  // class_start_[b·(K+1) + c + 1]).
  // (The pairs are the arrays' first pair_count_: their size only grows, so that a build writes
  // no zeros over them.) A build lists the balls of sorted_ up to listed_, and has sorted the
  // first gap_sorted_ batches by gap.
  BigArray<int> pair_i_, pair_k_;
  int pair_count_ = 0, listed_ = 0, gap_sorted_ = 0;
  BigArray<double> pair_d2_;  // (a build's: the pairs' squared distances then, for their classes)
  std::vector<int> class_start_;
  // From the pair pass's batch b on, no pair has a body numbered below frontier_[b]: those are
  // moved to the end of the step after batch b − 1. (frontier_[batches] = every body.)
  std::vector<int> frontier_;
  BigArray<int> neighbour_start_, neighbours_;  // both ways, by ball: ball i's are [start[i], start[i + 1])
  struct NearFace {
    int ball, wall;
  };
  std::vector<NearFace> near_faces_;  // box faces within a ball's reach
  std::vector<int> outside_window_;   // (a build's: pairs of balls, one of them near a face perhaps)
  std::vector<int> escaped_;

  // With many fast balls, the grid of their paths this step (path_grid.hpp), in which each
  // looks for the others (with a few, it tests every one).
  PathGrid<D> fast_paths_;
  bool fast_paths_on_ = false;
  double path_cell_ = 1;  // its cells' size
  size_t path_entries_ = 0;  // its entries when it was last entered whole
  std::vector<double> path_lengths_;  // (start_fast_paths's)

  // A ball in inelastic collapse, and the balls touching it, settled at once (contact_cluster.hpp).
  ContactCluster<D> cluster_;
  std::vector<int> cluster_balls_;
  long cluster_budget_ = 0;  // the work clusters may still take in this step (settle_cluster)
};

// A ball's grid cell (in every per-ball loop of the grid's build and the fast balls' searches: here,
// to be inlined in each file of the collisions that walks the grid).
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

// Called per contact from the drift (ball_collisions.cpp) and a few lines each: here, to be inlined there.
// (make_fast and mark_fast_if_needed belong with fast_balls.cpp, wall_restitution with wall_contacts.cpp.)
template <int D>
void BallCollisions<D>::make_fast(int i) {
  if (!state_[i].fast) state_[i].fast = true, fast_.push_back(i);
  if (!state_[i].escaped) state_[i].escaped = true, escaped_.push_back(i);
}

template <int D>
void BallCollisions<D>::mark_fast_if_needed(int i, double t) {
  if (state_[i].fast || radius_of(i) <= 0) return;
  if (state_[i].travelled + velocity(i).norm() * (h_ - t) > sweep_) make_fast(i);  // (and off the lists)
}

template <int D>
double BallCollisions<D>::wall_restitution(int wall) const {
  return wall < static_cast<int>(planes_.size()) ? planes_[static_cast<size_t>(wall)].restitution
                                                 : segments_[static_cast<size_t>(wall) - planes_.size()].restitution;
}

extern template class BallCollisions<1>;
extern template class BallCollisions<2>;
extern template class BallCollisions<3>;

}  // namespace motus
