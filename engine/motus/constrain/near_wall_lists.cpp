// The walls' broad phase: for each wall, the free bodies near it, kept across projections. Its own
// part: it is made once a projection (and rebuilt seldom), outside the sweeps, which only read its lists.
#include "motus/constrain/constraint_projection.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "motus/constrain/wall_height.hpp"

namespace motus {
namespace {

// Whether a push out of wall a, along its normal, may move a body into wall b. It brings the body
// nearer to b when their normals point against each other (n_a·n_b < 0) — but not into it when
// the two are opposite faces (n_a = −n_b, like a box's two faces along one axis) more than
// `clearance` apart: the push leaves the body on a's surface, and a body on one face is then more
// than clearance − 2r from the other. (Perpendicular faces, n_a·n_b = 0, leave its height above b
// as it was.)
template <class Wall>
bool may_push_into(const Wall& a, const Wall& b, double clearance) {
  double cosine = 0;
  bool opposite = true;
  for (size_t k = 0; k < a.normal.size(); ++k) {
    cosine += a.normal[k] * b.normal[k];
    opposite = opposite && a.normal[k] == -b.normal[k];
  }
  if (!(cosine < 0)) return false;
  const double apart = -b.offset - a.offset;  // opposite: the free slab a.offset ≤ n_a·x ≤ −b.offset
  return !(opposite && apart > clearance);
}

}  // namespace

// The walls' broad phase, at the start of a projection: for each wall (plane or box face), the
// free bodies that may meet it during the sweeps. Within the sweeps a body moves by their
// corrections: ball pushes, which the ball pairs' margin (the largest radius) covers as it does for
// the pairs (find_ball_pairs); stick corrections, each by its stick's error, which in a scene whose
// sticks hold stays well under the stick's rest length; and the walls' own pushes, by however deep
// the body was in. So wall w's list holds the bodies whose height above it, n·x − offset − r, is
// under that margin plus the longest stick (wall_margin_), and those near a wall whose push may
// send them into w (a wedge of two planes; find_walls_pushing_into_each_wall): tested against w in
// every sweep as before, not only in the last pass.
//
// Making the lists costs a pass over every body and wall, so they are kept across projections as
// the ball pairs' list is: they hold the bodies within wall_margin_ + wall_skin_, and serve until
// some body has moved the skin since they were made (one pass over the bodies, a quarter of a pass
// over a 2-D box's four walls). Walls do not move, so a body left off a wall's list, then at least
// margin + skin from it, is still at least the margin from it after moving less than the skin.
//
// What is guaranteed, and what is the same as testing every body in every pass:
// - No body ends a projection inside a wall: the last wall pass tests every body (project()), as
//   before (in a wedge, the second wall's push may still leave a body a little in the first, as
//   before).
// - The positions are the same to the last bit whenever no body is inside a wall whose list it is
//   not on at one of the sweeps' wall passes: testing a body that is outside a wall changes
//   nothing, so leaving it out changes nothing, and each listed body meets the walls in the same
//   order.
// - They differ only when sticks or ball pushes carry a body more than the margin into a wall
//   within one projection (a stick stretched to many times its length, a ball flung through a
//   packed heap): the sweeps leave it in the wall and the last pass puts it on the surface, so the
//   sweeps' sticks and contacts after it went in have not seen it there. That is no worse than what
//   the sweeps already allow (the contacts and sticks after the last sweep's wall pass never see
//   the walls either), and the lists of a later projection hold it, there on the surface.
void ConstraintProjection::find_bodies_near_walls(ConstVectorRef x) {
  if (walls_.empty()) return;
  bool still_hold = have_near_wall_lists_;
  if (still_hold) {
    switch (d_) {
      case 1: still_hold = near_wall_lists_still_hold<1>(x.data()); break;
      case 2: still_hold = near_wall_lists_still_hold<2>(x.data()); break;
      default: still_hold = near_wall_lists_still_hold<3>(x.data()); break;
    }
  }
  if (!still_hold) list_bodies_near_walls(x);
}

// Whether every body is still closer than the skin to where it was when the lists were made.
// (Written so that a NaN position, which compares false, makes them again.)
template <int D>
bool ConstraintProjection::near_wall_lists_still_hold(const double* x) const {
  const double limit2 = wall_skin_ * wall_skin_;
  const double* then = listed_at_.data();
  const size_t coordinates = listed_at_.size();
  for (size_t c = 0; c < coordinates; c += D) {
    double moved2 = 0;
    for (int k = 0; k < D; ++k) {
      const double step = x[c + k] - then[c + k];
      moved2 += step * step;
    }
    if (!(moved2 < limit2)) return false;
  }
  return true;
}

// The lists from scratch, and every body's position now.
void ConstraintProjection::list_bodies_near_walls(ConstVectorRef x) {
  switch (d_) {
    case 1: list_bodies_near_walls_in<1>(x.data()); break;
    case 2: list_bodies_near_walls_in<2>(x.data()); break;
    default: list_bodies_near_walls_in<3>(x.data()); break;
  }
  std::copy(x.begin(), x.end(), listed_at_.begin());
  have_near_wall_lists_ = true;
  ++near_wall_builds_;
}

// Wall w's list: the free bodies, in index order, within margin + skin of wall w or of a wall whose
// push may move them into it.
template <int D>
void ConstraintProjection::list_bodies_near_walls_in(const double* x) {
  const double reach = wall_margin_ + wall_skin_;
  for (auto& list : near_wall_) list.clear();
  const auto n = static_cast<int>(radius_.size());
  for (int i = 0; i < n; ++i) {
    if (inverse_mass_[i] == 0) continue;
    const double r = radius_[static_cast<size_t>(i)];
    for (size_t w = 0; w < walls_.size(); ++w) near_[w] = height_above<D>(walls_[w], r, x + D * i) < reach;
    for (size_t w = 0; w < walls_.size(); ++w) {
      bool listed = near_[w];
      for (const int a : pushed_in_by_[w]) listed = listed || near_[static_cast<size_t>(a)];
      if (listed) near_wall_[w].push_back(i);
    }
  }
}

// For each wall b, the other walls whose push may move a body into it (may_push_into), directly or
// through other walls (a pushes into c, which pushes into b). A body near one of them may be pushed
// into b during the sweeps from however far, so b's list holds it too. A box's faces push into
// none of each other, so a box alone has none; the opposite faces' clearance is a ball's diameter
// and the margin, the farthest a body on one face may still move towards the other.
void ConstraintProjection::find_walls_pushing_into_each_wall() {
  const double clearance = 2 * max_radius_ + wall_margin_;
  const size_t walls = walls_.size();
  pushed_in_by_.assign(walls, {});
  for (size_t b = 0; b < walls; ++b)
    for (size_t a = 0; a < walls; ++a)
      if (a != b && may_push_into(walls_[a], walls_[b], clearance)) pushed_in_by_[b].push_back(static_cast<int>(a));
  for (bool grew = true; grew;) {
    grew = false;
    for (size_t b = 0; b < walls; ++b)
      for (size_t u = 0; u < pushed_in_by_[b].size(); ++u) {
        const auto a = static_cast<size_t>(pushed_in_by_[b][u]);
        for (const int c : pushed_in_by_[a]) {
          auto& into_b = pushed_in_by_[b];
          if (static_cast<size_t>(c) != b && std::find(into_b.begin(), into_b.end(), c) == into_b.end()) {
            into_b.push_back(c);
            grew = true;
          }
        }
      }
  }
}

}  // namespace motus
