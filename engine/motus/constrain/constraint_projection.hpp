#pragma once
// Position-based constraints on velocityless Verlet (Jakobsen, "Advanced Character
// Physics"; the course's fabric-and-ragdoll demo, docs/course.md section 10): after the Verlet step moves every
// body, positions are projected back onto the constraints, a fixed number of sweeps:
//   each stick:  move its two ends along the stick, in proportion to their inverse
//                masses, until it has its rest length (in groups that share no body:
//                sweep_order.hpp); a chain of sticks instead gets one Newton iteration
//                on all its sticks at once, until it is exact (chain_solver.hpp);
//   each wall:   push a body that is inside a wall back to its surface (in the sweeps, only
//                the bodies listed near the wall: a broad phase kept across projections);
//   each pair of overlapping balls: push them apart, mass-weighted;
//   then the walls once more, every body (no body ends a step inside a wall), and
//   each pin:    put the body back on its point (pins go last, so they never move).
// The sweeps stop early when only chains are left and they are exact. The velocity is then
// the backward difference the positions imply, (x_{n+1} − x_n)/Δt (not the central one of an
// unprojected Verlet run: docs/course.md, section 4).
#include <array>
#include <utility>
#include <vector>

#include "motus/collide/colliders.hpp"
#include "motus/constrain/chain_solver.hpp"
#include "motus/constrain/constraints.hpp"
#include "motus/constrain/sweep_order.hpp"
#include "motus/vector.hpp"

namespace motus {

class ConstraintProjection {
public:
  // `order`: the sticks swept in the scene's order (its exact numbers) or by colours (for substeps).
  ConstraintProjection(int dimensions, const Vector& inverse_mass, std::vector<double> radius,
                       std::vector<StickConstraint> sticks, std::vector<PinConstraint> pins,
                       const Colliders& colliders, int iterations, SweepOrder order = SweepOrder::scene);

  // `iterations` sweeps over sticks, walls and ball pairs (in the constructor's order), then the pins.
  void project(VectorRef x);
  // Only the contacts between balls, `iterations` sweeps (after a projection from outside,
  // which moves sticks, pins and walls but not balls against each other).
  void push_balls_apart(VectorRef x);

  // The largest |length − rest length| / rest length over the sticks (0 without sticks).
  double max_relative_stick_error(ConstVectorRef x) const;
  // The farthest any pinned body is from its pin (0 after motus's own projection, which places
  // the pins last; a plug-in's projection may leave one off).
  double max_pin_distance(ConstVectorRef x) const;
  bool has_pins() const { return !pins_.empty(); }
  bool pinned(int body) const;

  // Hash buckets looked into by the ball pairs' broad phase, over every projection so far: a
  // projection that reuses the neighbour list looks into none.
  long broad_phase_queries() const { return broad_phase_queries_; }
  // How many times the neighbour list of the ball pairs was built (the first projection with two
  // balls or more, then each one that finds a ball moved more than half the skin since the last).
  long ball_pair_builds() const { return ball_pair_builds_; }
  // Body–wall tests made by the sweeps' wall passes over the near-wall lists (planes and box faces),
  // over every projection so far; the pass over every body that ends a projection is not counted.
  // Without the lists it would be (walls × free bodies) for each of those passes.
  long near_wall_tests() const { return near_wall_tests_; }
  // How many times the near-wall lists were made (the first projection whose sweeps use them, then
  // each one that finds a body moved farther than the lists' skin since the last).
  long near_wall_builds() const { return near_wall_builds_; }

  // A wall in the one form the sweep needs: the free half-space n·x ≥ offset, |n| = 1.
  struct Wall {
    std::array<double, 3> normal{0, 0, 0};
    double offset = 0;
  };
  // The scene's planes, and each box container's inward faces.
  const std::vector<Wall>& walls() const { return walls_; }

private:
  void place_pins(VectorRef x) const;
  void project_sticks(VectorRef x) const;
  void project_walls(VectorRef x) const;
  void find_bodies_near_walls(ConstVectorRef x);
  template <int D>
  bool near_wall_lists_still_hold(const double* x) const;
  void list_bodies_near_walls(ConstVectorRef x);
  template <int D>
  void list_bodies_near_walls_in(const double* x);
  void find_walls_pushing_into_each_wall();
  void project_bodies_near_walls(VectorRef x);
  void project_segments(VectorRef x) const;
  void project_segment(size_t j, int i, VectorRef xi) const;
  void remember_segment_sides(ConstVectorRef x);
  void find_ball_pairs(ConstVectorRef x);
  template <int D>
  void find_ball_pairs_in(const double* x);
  template <int D>
  bool neighbours_still_hold(const double* x) const;
  template <int D>
  void build_neighbours(const double* x);
  template <int D>
  void select_close_pairs(const double* x);
  void project_ball_pairs(VectorRef x) const;

  int d_;
  Vector inverse_mass_;  // pinned bodies count as infinitely heavy
  std::vector<double> radius_;
  std::vector<StickConstraint> sticks_;
  // The sticks as the sweep reads them: group by group (sweep_order.hpp), each with its
  // ends' shares of a correction, w_a/(w_a + w_b) and w_b/(w_a + w_b), worked out once
  // (pins never change, so neither do they); sticks between two pinned bodies are left out.
  struct SweepStick {
    int a, b;
    double length, share_a, share_b;
  };
  std::vector<SweepStick> sweep_sticks_;
  std::vector<int> sweep_group_start_;  // group g: sweep_sticks_[start[g] .. start[g + 1])
  // Chains of two or more sticks (a rope) are not swept but solved all at once, one Newton
  // iteration per sweep until they are exact (chain_solver.hpp).
  ChainSolver chains_;
  std::vector<PinConstraint> pins_;
  Colliders colliders_;
  int iterations_;
  long broad_phase_queries_ = 0;
  long ball_pair_builds_ = 0;

  std::vector<Wall> walls_;  // planes, and each box's inward faces
  std::vector<int> balls_;   // bodies with radius > 0
  double max_radius_ = 0;
  std::vector<signed char> side_;  // body i's side of segment j (+1, −1; 0: not yet seen)

  // The walls' broad phase (sized in the constructor), kept across projections like the ball
  // pairs' list: for wall w, the free bodies whose surface was within wall_margin_ + wall_skin_ of
  // it, or of a wall whose push may move a body into it (pushed_in_by_[w]; none for a box's faces),
  // when the lists were made, in index order (near_wall_[w]); every body's position then
  // (listed_at_); and which walls the body being listed is near (near_). The sweeps' wall passes
  // test only the listed bodies. The margin: how far a body may move during one projection's
  // sweeps (near_wall_lists.cpp, find_bodies_near_walls).
  double wall_margin_ = 0, wall_skin_ = 0;
  std::vector<std::vector<int>> pushed_in_by_;
  bool have_near_wall_lists_ = false;
  std::vector<std::vector<int>> near_wall_;
  std::vector<double> listed_at_;
  std::vector<char> near_;
  long near_wall_tests_ = 0;
  long near_wall_builds_ = 0;

  // Broad phase (sized in the constructor). A neighbour ("Verlet") list kept across projections:
  // the pairs closer than r_a + r_b + margin + skin when it was built, sorted by (i, k), and each
  // ball's position then (ball s of balls_: built_at_[s·d .. s·d + d)); the hash that builds it
  // (balls counting-sorted by bucket); and the candidate pairs the sweeps test, the neighbours
  // closer than r_a + r_b + margin at the projection's start (in the same order).
  double margin_ = 0, skin_ = 0;
  bool have_neighbours_ = false;
  std::vector<std::pair<int, int>> neighbours_;
  std::vector<double> built_at_;
  std::vector<int> bucket_start_, bucket_of_, sorted_;
  std::vector<std::pair<int, int>> pairs_;
};

}  // namespace motus
