#include "motus/constrain/constraint_projection.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "motus/constrain/stick_chains.hpp"
#include "motus/constrain/sweep_order.hpp"
#include "motus/constrain/wall_height.hpp"
#include "motus/scene_error.hpp"

// Jakobsen's relaxation ("Advanced Character Physics", 2001), as the course's fabric and
// ragdoll demo runs it. Each constraint on its own is easy: a stick that is too long
// moves its two ends towards each other until it has its length; a body inside a wall
// moves to the wall's surface. Satisfying one breaks its neighbours a little, so we
// sweep over all of them a fixed number of times: every sweep shrinks the errors, and
// what is left after `iterations` sweeps is the cloth's stretchiness. A single stick is
// satisfied exactly by one projection; a cloth needs more sweeps the more sticks a
// disturbance has to travel through.
//
// The projection changes positions only. Verlet reads the velocity from the positions
// (x_{n+1} − x_n)/Δt, so a projected body also gets the velocity that the projection
// implies: a particle pushed out of the floor stops falling without any impulse.
//
// The two broad phases kept across projections are their own parts, as are the 2-D segments:
// near_wall_lists.cpp, ball_pair_neighbours.cpp and segment_colliders.cpp; the numbers that size
// the broad phases stay here, with the constructor that sizes them.

namespace motus {
namespace {

// Cells of the broad phase are hashed into a table of this many buckets per ball (a
// power of two at least this large): few enough to stay small, enough that unrelated
// cells seldom share a bucket.
constexpr int kBucketsPerBall = 2;

// Chains of at least this many sticks are solved directly; a single stick is exact after one
// projection anyway, so it stays in the sweep.
constexpr int kShortestSolvedChain = 2;
// A chain is exact when no stick is off its length by more than this fraction.
constexpr double kChainTolerance = 1e-12;

// The neighbour list's skin, in radii of the largest ball. The list holds the pairs closer than
// r_a + r_b + margin + skin and serves until some ball has moved half the skin: a thicker skin is
// built less often but holds more pairs, which every projection looks through once. Measured at
// 1/60 s (2026-12-07): in ball_gas's lattice (10,000 balls, speeds up to 1.4 m/s) skins of 0.5, 1,
// 2 and 3 radii built the list every 6, 12, 23 and 33 steps, and the broad phase with one sweep
// took 1.9, 1.33, 1.16 and 1 times the 3-radii skin's time (a hash every projection: 8.7 times);
// in a packed heap falling onto a floor (2,000 balls, 2-D and 3-D) 2 radii was 6–7 % faster than
// 1 and 3 no faster than 2: a packed heap's list grows as the d-th power of the reach, and beyond
// 2 radii that outweighs the builds saved.
constexpr double kSkinPerRadius = 2;

// Room reserved for the neighbour list, per ball. Equal balls packed as tightly as they go have,
// within 5 radii (r_a + r_b + margin + skin with the skin above), 18 neighbours in 2-D
// (hexagonal) and 86 in 3-D (face-centred cubic), each pair listed once: 9 and 43 a ball. A scene
// that needs more than reserved grows the list geometrically, a few times at most, and it keeps
// its capacity from then on.
constexpr size_t kNeighboursPerBall = 12;

// The near-wall lists' skin, in margins (the margin: how far a body may move during one
// projection's sweeps; find_bodies_near_walls). The lists hold the bodies within margin + skin of
// a wall and serve until some body has moved the skin. Any skin is correct; with this one
// ball_gas (margin 0.5 m, balls up to 1.4 m/s, 0.024 m a step) makes its lists once in 20 steps
// (400 balls: 6 times in 121 projections), and they hold little more than the outer rows.
constexpr double kWallSkinPerMargin = 1;

}  // namespace

ConstraintProjection::ConstraintProjection(int dimensions, const Vector& inverse_mass, std::vector<double> radius,
                                           std::vector<StickConstraint> sticks, std::vector<PinConstraint> pins,
                                           const Colliders& colliders, int iterations, SweepOrder order)
    : d_(dimensions), inverse_mass_(inverse_mass), radius_(std::move(radius)), sticks_(std::move(sticks)),
      pins_(std::move(pins)), colliders_(colliders), iterations_(iterations) {
  const int n = static_cast<int>(inverse_mass_.size());
  if (d_ < 1 || d_ > 3) throw SceneError("dimensions", "constraints need 1, 2 or 3 dimensions");
  if (iterations_ < 1)
    throw SceneError("constraint_iterations", "must be at least 1 (" + std::to_string(iterations_) + " given)");
  auto check_body = [n](int body, const std::string& field) {
    if (body < 0 || body >= n)
      throw SceneError(field, "body " + std::to_string(body) + " does not exist: the scene has bodies 0.." +
                                  std::to_string(n - 1));
  };
  for (size_t s = 0; s < sticks_.size(); ++s) {
    const std::string field = "sticks[" + std::to_string(s) + "]";
    check_body(sticks_[s].a, field + ".a");
    check_body(sticks_[s].b, field + ".b");
    if (sticks_[s].a == sticks_[s].b) throw SceneError(field, "a stick needs two different bodies");
    if (!(sticks_[s].length > 0)) throw SceneError(field + ".length", "a stick's rest length must be > 0");
  }
  for (size_t p = 0; p < pins_.size(); ++p) check_body(pins_[p].body, "pins[" + std::to_string(p) + "].body");
  // A pinned body is infinitely heavy: sticks and contacts move only its partners.
  for (const auto& p : pins_) inverse_mass_[p.body] = 0;
  // Chains of sticks are solved directly (chain_solver.hpp); the other sticks are swept in
  // groups that share no body (sweep_order.hpp).
  std::vector<StickChain> chains = find_stick_chains(sticks_, inverse_mass_, kShortestSolvedChain);
  std::vector<char> in_chain(sticks_.size(), 0);
  for (const auto& c : chains)
    for (int s : c.sticks) in_chain[static_cast<size_t>(s)] = 1;
  chains_ = ChainSolver(d_, inverse_mass_, sticks_, std::move(chains));
  const StickGroups groups = sweep_groups(sticks_, n, order);
  sweep_group_start_.push_back(0);
  for (int g = 0; g < groups.groups(); ++g) {
    for (int u = groups.group_start[static_cast<size_t>(g)]; u < groups.group_start[static_cast<size_t>(g) + 1]; ++u) {
      const auto index = static_cast<size_t>(groups.order[static_cast<size_t>(u)]);
      const StickConstraint& stick = sticks_[index];
      const double wa = inverse_mass_[stick.a], wb = inverse_mass_[stick.b];
      if (wa + wb == 0 || in_chain[index]) continue;  // both ends pinned: nothing may move
      sweep_sticks_.push_back({stick.a, stick.b, stick.length, wa / (wa + wb), wb / (wa + wb)});
    }
    if (sweep_group_start_.back() != static_cast<int>(sweep_sticks_.size()))
      sweep_group_start_.push_back(static_cast<int>(sweep_sticks_.size()));
  }

  // Walls, in the one form the sweep needs: a box container is its 2·d inward faces.
  for (const auto& p : colliders_.planes) {
    double length = 0;
    for (int k = 0; k < d_; ++k) length += p.normal[k] * p.normal[k];
    length = std::sqrt(length);
    if (!(length > 0)) throw SceneError("colliders", "a plane's normal must not be zero");
    Wall w;
    for (int k = 0; k < d_; ++k) w.normal[k] = p.normal[k] / length;
    w.offset = p.offset / length;
    walls_.push_back(w);
  }
  for (const auto& b : colliders_.boxes)
    for (int k = 0; k < d_; ++k) {
      Wall low, high;
      low.normal[k] = 1;
      low.offset = b.min[k];
      high.normal[k] = -1;
      high.offset = -b.max[k];
      walls_.push_back(low);
      walls_.push_back(high);
    }
  if (!colliders_.segments.empty() && d_ != 2)
    throw SceneError("colliders", "segment colliders exist in 2-D scenes only");

  for (int i = 0; i < n; ++i)
    if (radius_[i] > 0) {
      balls_.push_back(i);
      max_radius_ = std::max(max_radius_, radius_[i]);
    }

  // Everything project() touches is sized here, so a step allocates nothing.
  side_.assign(static_cast<size_t>(n) * colliders_.segments.size(), 0);
  if (balls_.size() >= 2) {
    int buckets = 1;
    while (buckets < kBucketsPerBall * static_cast<int>(balls_.size())) buckets *= 2;
    bucket_start_.assign(static_cast<size_t>(buckets) + 1, 0);
    bucket_of_.resize(balls_.size());
    sorted_.resize(balls_.size());
    built_at_.resize(balls_.size() * static_cast<size_t>(d_));
    neighbours_.reserve(kNeighboursPerBall * balls_.size());
    // Each pair is listed once, so equal balls packed as tightly as they go (12 neighbours
    // in 3-D) give 6 per ball; 8 leaves room for the margin. A scene that needs more
    // grows the list once, and it keeps its capacity from then on.
    pairs_.reserve(8 * balls_.size());
  }
  // The margin covers how far balls move against each other during the sweeps of one projection;
  // the skin, how far they may move between the list's builds.
  margin_ = max_radius_;
  skin_ = kSkinPerRadius * max_radius_;

  // The walls' broad phase (find_bodies_near_walls): a list holds at most every body, so none
  // grows in a step.
  double longest_stick = 0;
  for (const auto& s : sticks_) longest_stick = std::max(longest_stick, s.length);
  wall_margin_ = margin_ + longest_stick;
  wall_skin_ = kWallSkinPerMargin * wall_margin_;
  if (!walls_.empty()) {
    find_walls_pushing_into_each_wall();
    near_wall_.assign(walls_.size(), {});
    for (auto& list : near_wall_) list.reserve(static_cast<size_t>(n));
    listed_at_.resize(static_cast<size_t>(n) * static_cast<size_t>(d_));
    near_.resize(walls_.size());
  }
}

bool ConstraintProjection::pinned(int body) const { return inverse_mass_[body] == 0; }

void ConstraintProjection::project(VectorRef x) {
  place_pins(x);  // first, so the sticks pull towards where the pins really are
  if (balls_.size() >= 2) find_ball_pairs(x);
  // Once the chains are exact, a sweep with nothing else to do would change nothing.
  const bool only_chains = sweep_sticks_.empty() && walls_.empty() && colliders_.segments.empty() && pairs_.empty();
  // Walls win: the projection's last wall pass tests every body against every wall, so that no
  // body ends it inside a wall, whatever the sweeps did; while a stick a little off its length is
  // only stretchiness, a body seen through the floor is a bug. (Sweeps are what make sticks and
  // contacts agree; this only settles who is last.) Ball pushes, segments or a second wall may
  // move a body after a sweep's wall pass: then that last pass comes after the sweeps. With no
  // ball pairs and a single plane (a cloth's floor) the last sweep's own wall pass is the last,
  // and it is the one over every body. The sweeps' other wall passes test only the bodies listed
  // near each wall (find_bodies_near_walls).
  const bool wall_pass_after_sweeps = !pairs_.empty() || !colliders_.segments.empty() || walls_.size() > 1;
  const int sweeps_near_walls = wall_pass_after_sweeps ? iterations_ : iterations_ - 1;
  if (sweeps_near_walls > 0) find_bodies_near_walls(x);
  for (int sweep = 0; sweep < iterations_; ++sweep) {
    project_sticks(x);
    const bool chains_exact = chains_.iterate(x.data(), kChainTolerance);
    if (only_chains && chains_exact) break;
    if (sweep < sweeps_near_walls)
      project_bodies_near_walls(x);
    else
      project_walls(x);
    project_ball_pairs(x);
  }
  if (wall_pass_after_sweeps) project_walls(x);
  place_pins(x);  // last, exactly: nothing above moves a body of inverse mass 0, but be sure
  remember_segment_sides(x);
}

void ConstraintProjection::push_balls_apart(VectorRef x) {
  if (balls_.size() < 2) return;
  find_ball_pairs(x);
  for (int sweep = 0; sweep < iterations_; ++sweep) project_ball_pairs(x);
}

void ConstraintProjection::place_pins(VectorRef x) const {
  for (const auto& p : pins_)
    for (int k = 0; k < d_; ++k) x[p.body * d_ + k] = p.position[k];
}

// Move both ends along the stick, each by its share of the error: the lighter body moves
// more (shares w_a/(w_a+w_b) and w_b/(w_a+w_b) of the inverse masses), so the stick's
// centre of mass stays where it was and the projection adds no momentum.
namespace {

// One stick: with Δ = x_b − x_a and d = |Δ|, the correction (d − L)/d · Δ, shared by the
// precomputed inverse-mass shares.
template <int D, class Stick>
inline void project_stick(const Stick& s, double* x) {
  double* xa = x + D * s.a;
  double* xb = x + D * s.b;
  double delta[D];
  double length2 = 0;
  for (int k = 0; k < D; ++k) {
    delta[k] = xb[k] - xa[k];
    length2 += delta[k] * delta[k];
  }
  if (length2 == 0) return;  // the two ends coincide: no direction to push along
  const double length = std::sqrt(length2);
  const double stretch = (length - s.length) / length;
  const double move_a = stretch * s.share_a, move_b = stretch * s.share_b;
  for (int k = 0; k < D; ++k) {
    xa[k] += move_a * delta[k];
    xb[k] -= move_b * delta[k];
  }
}

// Two sticks of one group (no body in common) at once, in the two lanes of a SIMD
// register (Eigen's Array2d: SSE2 on x86-64): the same arithmetic, so the same numbers as
// one at a time, for one square root and one division of two lanes.
template <int D, class Stick>
inline void project_stick_pair(const Stick& s, const Stick& t, double* x) {
  using Lanes = Eigen::Array2d;
  double* xa0 = x + D * s.a;
  double* xb0 = x + D * s.b;
  double* xa1 = x + D * t.a;
  double* xb1 = x + D * t.b;
  Lanes delta[D];
  Lanes length2 = Lanes::Zero();
  for (int k = 0; k < D; ++k) {
    delta[k] = Lanes(xb0[k], xb1[k]) - Lanes(xa0[k], xa1[k]);
    length2 += delta[k] * delta[k];
  }
  if (length2[0] == 0 || length2[1] == 0) {  // (rare) coincident ends: one at a time
    project_stick<D>(s, x);
    project_stick<D>(t, x);
    return;
  }
  const Lanes length = length2.sqrt();
  const Lanes stretch = (length - Lanes(s.length, t.length)) / length;
  const Lanes move_a = stretch * Lanes(s.share_a, t.share_a), move_b = stretch * Lanes(s.share_b, t.share_b);
  for (int k = 0; k < D; ++k) {
    const Lanes da = move_a * delta[k], db = move_b * delta[k];
    xa0[k] += da[0];
    xa1[k] += da[1];
    xb0[k] -= db[0];
    xb1[k] -= db[1];
  }
}

// One sweep over the sticks, group by group, with the dimension known at compile time:
// this is the inner loop of a cloth (thousands of sticks, every step).
template <int D, class Stick>
void project_sticks_in(const std::vector<Stick>& sticks, const std::vector<int>& group_start, double* x) {
  const Stick* stick = sticks.data();
  for (size_t g = 0; g + 1 < group_start.size(); ++g) {
    int u = group_start[g];
    const int end = group_start[g + 1];
    for (; u + 1 < end; u += 2) project_stick_pair<D>(stick[u], stick[u + 1], x);
    if (u < end) project_stick<D>(stick[u], x);
  }
}

}  // namespace

void ConstraintProjection::project_sticks(VectorRef x) const {
  switch (d_) {
    case 1: project_sticks_in<1>(sweep_sticks_, sweep_group_start_, x.data()); break;
    case 2: project_sticks_in<2>(sweep_sticks_, sweep_group_start_, x.data()); break;
    default: project_sticks_in<3>(sweep_sticks_, sweep_group_start_, x.data()); break;
  }
}

namespace {

// A body inside the wall moves along the normal back to its surface; one outside stays, untouched.
template <int D, class Wall>
inline void push_out_of_wall(const Wall& wall, double r, double* xi) {
  const double height = height_above<D>(wall, r, xi);
  if (height < 0)
    for (int k = 0; k < D; ++k) xi[k] -= height * wall.normal[k];
}

// Every free body against every wall, body by body, with the dimension known at compile time
// (a gas in its box: 10,000 balls against 4 walls, every step). Each body meets the walls in the
// scene's order; a body's corrections move no other body, so this is the same to the last bit as
// going wall by wall.
template <int D, class Wall>
void project_every_body_in(const std::vector<Wall>& walls, const Vector& inverse_mass,
                           const std::vector<double>& radius, double* x) {
  const auto n = static_cast<int>(radius.size());
  for (int i = 0; i < n; ++i) {
    if (inverse_mass[i] == 0) continue;  // pinned: the pin wins
    const double r = radius[static_cast<size_t>(i)];
    for (const Wall& wall : walls) push_out_of_wall<D>(wall, r, x + D * i);
  }
}

// Wall w against the bodies of list w only, wall by wall: each listed body meets the walls in the
// scene's order, as in a pass over every body.
template <int D, class Wall>
void project_listed_bodies_in(const std::vector<Wall>& walls, const std::vector<std::vector<int>>& lists,
                              const std::vector<double>& radius, double* x) {
  for (size_t w = 0; w < walls.size(); ++w)
    for (const int i : lists[w]) push_out_of_wall<D>(walls[w], radius[static_cast<size_t>(i)], x + D * i);
}

}  // namespace

// The projection's last wall pass: every free body against every wall, then every segment.
void ConstraintProjection::project_walls(VectorRef x) const {
  switch (d_) {
    case 1: project_every_body_in<1>(walls_, inverse_mass_, radius_, x.data()); break;
    case 2: project_every_body_in<2>(walls_, inverse_mass_, radius_, x.data()); break;
    default: project_every_body_in<3>(walls_, inverse_mass_, radius_, x.data()); break;
  }
  project_segments(x);
}

// A sweep's wall pass: each wall against the bodies listed near it, then every segment (every
// body: segments have no broad phase).
void ConstraintProjection::project_bodies_near_walls(VectorRef x) {
  switch (d_) {
    case 1: project_listed_bodies_in<1>(walls_, near_wall_, radius_, x.data()); break;
    case 2: project_listed_bodies_in<2>(walls_, near_wall_, radius_, x.data()); break;
    default: project_listed_bodies_in<3>(walls_, near_wall_, radius_, x.data()); break;
  }
  for (const auto& list : near_wall_) near_wall_tests_ += static_cast<long>(list.size());
  project_segments(x);
}

namespace {

// Two overlapping balls move apart along the line of their centres until they touch,
// shared by inverse mass like a stick's ends (a contact is a stick that only pushes); with the
// dimension known at compile time (a gas: every candidate pair, every sweep).
template <int D>
void project_ball_pairs_in(const std::vector<std::pair<int, int>>& pairs, const Vector& inverse_mass,
                           const std::vector<double>& radius, double* x) {
  for (const auto& [i, k] : pairs) {
    const double wi = inverse_mass[i], wk = inverse_mass[k];
    const double w = wi + wk;
    if (w == 0) continue;
    double* xi = x + D * i;
    double* xk = x + D * k;
    double delta[D];
    double distance2 = 0;
    for (int c = 0; c < D; ++c) {
      delta[c] = xk[c] - xi[c];
      distance2 += delta[c] * delta[c];
    }
    const double touching = radius[static_cast<size_t>(i)] + radius[static_cast<size_t>(k)];
    if (distance2 >= touching * touching) continue;
    const double distance = std::sqrt(distance2);
    // Move along delta by depth·delta, so that they end touching. Coincident centres have no
    // direction of their own: any will do, and then the whole contact distance is the depth.
    double depth = (touching - distance) / distance;
    if (distance == 0) {
      for (int c = 0; c < D; ++c) delta[c] = c == 0 ? 1 : 0;
      depth = touching;
    }
    const double move_i = depth * wi / w, move_k = depth * wk / w;
    for (int c = 0; c < D; ++c) {
      xi[c] -= move_i * delta[c];
      xk[c] += move_k * delta[c];
    }
  }
}

}  // namespace

void ConstraintProjection::project_ball_pairs(VectorRef x) const {
  switch (d_) {
    case 1: project_ball_pairs_in<1>(pairs_, inverse_mass_, radius_, x.data()); break;
    case 2: project_ball_pairs_in<2>(pairs_, inverse_mass_, radius_, x.data()); break;
    default: project_ball_pairs_in<3>(pairs_, inverse_mass_, radius_, x.data()); break;
  }
}

double ConstraintProjection::max_relative_stick_error(ConstVectorRef x) const {
  double worst = 0;
  for (const auto& s : sticks_) {
    const double length = (x.segment(s.b * d_, d_) - x.segment(s.a * d_, d_)).norm();
    // (std::max drops a NaN: a stick between bodies no longer finite read as the others' error)
    if (std::isnan(length)) return length;
    worst = std::max(worst, std::abs(length - s.length) / s.length);
  }
  return worst;
}

double ConstraintProjection::max_pin_distance(ConstVectorRef x) const {
  double worst = 0;
  for (const auto& p : pins_) {
    const double distance = (x.segment(p.body * d_, d_) - Eigen::Map<const Vector>(p.position.data(), d_)).norm();
    worst = std::isnan(distance) ? distance : std::max(worst, distance);  // (a NaN position is off its pin)
    if (std::isnan(worst)) break;
  }
  return worst;
}

}  // namespace motus
