#include "motus/collide/ball_collisions.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "motus/collide/impulse.hpp"
#include "motus/collide/time_of_impact.hpp"

namespace motus {
namespace {

// After this many collisions in one step, a ball's inelastic contacts (e < 1) become
// perfectly inelastic (e = 0): stops the endless chatter of "inelastic collapse" (a ball
// trapped between two others losing a fraction of its speed at every touch) without
// touching elastic scenes.
constexpr unsigned kCollapseLimit = 64;

}  // namespace

template <int D>
BallCollisions<D>::BallCollisions(const Vector& inverse_mass, std::vector<double> radius,
                                  std::vector<double> restitution, const Colliders& colliders)
    : n_(static_cast<int>(inverse_mass.size())), inverse_mass_(inverse_mass), radius_(std::move(radius)),
      restitution_(std::move(restitution)) {
  for (int i = 0; i < n_; ++i) {
    max_radius_ = std::max(max_radius_, radius_[i]);
    if (radius_[i] > 0) balls_.push_back(i);
  }
  for (const auto& p : colliders.planes) {
    Point n;
    for (int k = 0; k < D; ++k) n[k] = p.normal[k];
    const double length = n.norm();
    planes_.push_back({n / length, p.offset / length, p.restitution});
  }
  for (const auto& b : colliders.boxes)  // a container: one inward-facing plane per face
    for (int k = 0; k < D; ++k) {
      Point n = Point::Zero();
      n[k] = 1;
      planes_.push_back({n, b.min[k], b.restitution});
      planes_.push_back({-n, -b.max[k], b.restitution});
    }
  if constexpr (D == 2) {
    for (const auto& s : colliders.segments) segments_.push_back({{s.a[0], s.a[1]}, {s.b[0], s.b[1]}, s.restitution});
  } else if (!colliders.segments.empty()) {
    throw std::invalid_argument("segment colliders exist in 2-D scenes only");
  }
  local_time_.resize(n_);
  travelled_.resize(n_);
  collision_count_.assign(n_, 0);
  collisions_this_step_.resize(n_);
  fast_flag_.resize(n_);
  ball_cell_.resize(n_);
}

template <int D>
void BallCollisions<D>::advance(int i, double t) {
  const double dt = t - local_time_[i];
  if (dt <= 0) return;
  position(i) += velocity(i) * dt;
  travelled_[i] += velocity(i).norm() * dt;
  local_time_[i] = t;
}

template <int D>
void BallCollisions<D>::drift(VectorRef x, VectorRef v, double h) {
  x_ = x.data();
  v_ = v.data();
  h_ = h;
  std::fill(local_time_.begin(), local_time_.end(), 0.0);
  std::fill(travelled_.begin(), travelled_.end(), 0.0);
  std::fill(collisions_this_step_.begin(), collisions_this_step_.end(), 0u);
  std::fill(fast_flag_.begin(), fast_flag_.end(), 0);
  fast_.clear();
  events_.clear();
  events_this_step_ = 0;

  // A ball that moves farther than the largest radius in this step is fast; the grid's
  // cells are sized for the slow ones.
  sweep_ = 0;
  for (int i : balls_) {
    const double s = velocity(i).norm() * h;
    if (s <= max_radius_) {
      sweep_ = std::max(sweep_, s);
    } else {
      fast_flag_[i] = 1;
      fast_.push_back(i);
    }
  }
  if (balls_.size() >= 2) build_grid();
  find_initial_events();

  const long limit = 1000 + 100 * static_cast<long>(n_);
  while (!events_.empty()) {
    std::pop_heap(events_.begin(), events_.end(), std::greater<>());
    const Event e = events_.back();
    events_.pop_back();
    if (collision_count_[e.i] != e.count_i) continue;  // stale: i has collided since
    if (e.other >= 0 && collision_count_[e.other] != e.count_other) continue;
    if (++events_this_step_ > limit)
      throw std::runtime_error("more than " + std::to_string(limit) +
                               " collisions in one step: the scene cannot settle (overlapping bodies?)");
    resolve(e);
  }
  for (int i = 0; i < n_; ++i) advance(i, h);
}

template <int D>
void BallCollisions<D>::build_grid() {
  ++counters_.grid_builds;
  // Two slow balls that meet within h started at most r_a + r_b + 2·sweep apart.
  cell_size_ = 2 * max_radius_ + 2 * sweep_;
  Point low = Point::Constant(INFINITY), high = Point::Constant(-INFINITY);
  long slow = 0;
  for (int i : balls_)
    if (!fast_flag_[i]) {
      low = low.cwiseMin(position(i));
      high = high.cwiseMax(position(i));
      ++slow;
    }
  if (slow == 0) {
    low.setZero();
    high.setZero();
  }
  origin_ = low;
  // Dense cells over the balls' extent, but never many more cells than balls (a sparse
  // scene gets bigger cells instead).
  for (;;) {
    double total = 1;
    for (int k = 0; k < D; ++k) {
      dims_[k] = static_cast<int>(std::min((high[k] - low[k]) / cell_size_, 1e6)) + 1;
      total *= dims_[k];
    }
    if (total <= 4.0 * static_cast<double>(slow) + 64) break;
    cell_size_ *= std::pow(total / (4.0 * static_cast<double>(slow) + 64), 1.0 / D) * 1.01;
  }
  int cells = 1;
  for (int k = 0; k < D; ++k) cells *= dims_[k];
  cell_start_.assign(static_cast<size_t>(cells) + 1, 0);
  for (int i : balls_)
    if (!fast_flag_[i]) {
      ball_cell_[i] = cell_of(position(i));
      ++cell_start_[static_cast<size_t>(cell_index(ball_cell_[i])) + 1];
    }
  for (int c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  sorted_.resize(static_cast<size_t>(slow));
  // Scatter (cell_start_ is used as the running insertion point, then shifted back).
  for (int i : balls_)
    if (!fast_flag_[i]) sorted_[cell_start_[cell_index(ball_cell_[i])]++] = i;
  for (int c = cells; c > 0; --c) cell_start_[c] = cell_start_[c - 1];
  cell_start_[0] = 0;
}

template <int D>
typename BallCollisions<D>::Cell BallCollisions<D>::cell_of(const Point& p) const {
  Cell c;
  for (int k = 0; k < D; ++k)
    c[k] = std::clamp(static_cast<int>(std::floor((p[k] - origin_[k]) / cell_size_)), 0, dims_[k] - 1);
  return c;
}

template <int D>
int BallCollisions<D>::cell_index(const Cell& c) const {
  int index = 0;
  for (int k = D - 1; k >= 0; --k) index = index * dims_[k] + c[k];
  return index;
}

template <int D>
template <class Visit>
void BallCollisions<D>::for_cells_in_box(const Point& low, const Point& high, Visit&& visit) {
  if (cell_start_.empty()) return;
  const Cell a = cell_of(low), b = cell_of(high);
  Cell c = a;
  for (;;) {
    ++counters_.cell_queries;
    const int index = cell_index(c);
    for (int s = cell_start_[index]; s < cell_start_[index + 1]; ++s) visit(sorted_[s]);
    int k = 0;
    while (k < D && c[k] == b[k]) c[k] = a[k], ++k;  // odometer over the box of cells
    if (k == D) break;
    ++c[k];
  }
}

template <int D>
void BallCollisions<D>::push(double t, int i, int other) {
  events_.push_back({t, i, other, collision_count_[i], other >= 0 ? collision_count_[other] : 0u});
  std::push_heap(events_.begin(), events_.end(), std::greater<>());
}

template <int D>
void BallCollisions<D>::separate_if_overlapping(int i, int k) {
  Point d = position(k) - position(i);
  const double R = radius_[i] + radius_[k];
  const double distance2 = d.squaredNorm();
  if (distance2 >= R * R * (1 - 1e-12)) return;
  const double w = inverse_mass_[i] + inverse_mass_[k];
  if (w == 0) return;
  const double distance = std::sqrt(distance2);
  Point n = Point::Zero();
  if (distance > 0) {
    n = d / distance;
  } else {
    n[0] = 1;  // coincident centres: any direction will do
  }
  const double depth = R - distance;
  position(i) -= (depth * inverse_mass_[i] / w) * n;
  position(k) += (depth * inverse_mass_[k] / w) * n;
  ++counters_.position_corrections;
}

template <int D>
void BallCollisions<D>::test_pair(int i, int k, double t) {
  ++counters_.pair_tests;
  const Point dp = position_at(k, t) - position_at(i, t);
  const Point dv = velocity(k) - velocity(i);
  const double R = radius_[i] + radius_[k];
  const double toi = sphere_sphere_impact(dp.squaredNorm(), dp.dot(dv), dv.squaredNorm(), R, h_ - t);
  if (toi != kNoImpact) push(t + toi, i, k);
}

template <int D>
void BallCollisions<D>::find_initial_events() {
  for (int i = 0; i < n_; ++i) {
    separate_from_walls(i);
    find_wall_events(i, 0);
  }
  if (balls_.size() < 2) return;
  // Slow pairs: each ball against the later balls of its own cell and the balls of its
  // "forward" neighbour cells, so every pair of neighbouring cells is visited once.
  static const std::vector<Cell> forward = [] {
    std::vector<Cell> offsets;  // the half of the 3^D − 1 neighbours whose last non-zero offset is +1
    int total = 1;
    for (int k = 0; k < D; ++k) total *= 3;
    for (int code = 0; code < total; ++code) {
      Cell o;
      for (int k = 0, c = code; k < D; ++k, c /= 3) o[k] = c % 3 - 1;
      int leading = 0;
      for (int k = D - 1; k >= 0 && leading == 0; --k) leading = o[k];
      if (leading > 0) offsets.push_back(o);
    }
    return offsets;
  }();
  for (size_t s = 0; s < sorted_.size(); ++s) {
    const int i = sorted_[s];
    const Cell& c = ball_cell_[i];
    const int index = cell_index(c);
    for (int u = static_cast<int>(s) + 1; u < cell_start_[index + 1]; ++u) {
      separate_if_overlapping(i, sorted_[u]);
      test_pair(i, sorted_[u], 0);
    }
    for (const Cell& o : forward) {
      Cell neighbour;
      bool inside = true;
      for (int k = 0; k < D; ++k) {
        neighbour[k] = c[k] + o[k];
        inside &= neighbour[k] >= 0 && neighbour[k] < dims_[k];
      }
      if (!inside) continue;
      ++counters_.cell_queries;
      const int m = cell_index(neighbour);
      for (int u = cell_start_[m]; u < cell_start_[m + 1]; ++u) {
        separate_if_overlapping(i, sorted_[u]);
        test_pair(i, sorted_[u], 0);
      }
    }
  }
  // Fast balls look along their whole path (and at each other).
  for (size_t a = 0; a < fast_.size(); ++a) {
    find_events(fast_[a], 0, -1);
  }
}

template <int D>
void BallCollisions<D>::separate_from_walls(int i) {
  for (const Plane& plane : planes_) {
    const double gap = plane.normal.dot(position(i)) - plane.offset - radius_[i];
    if (gap < 0) {
      position(i) -= gap * plane.normal;
      ++counters_.position_corrections;
    }
  }
  if constexpr (D == 2) {
    for (const Segment& s : segments_) {
      const Point along = s.b - s.a;
      const double reach = std::clamp(along.dot(position(i) - s.a) / along.squaredNorm(), 0.0, 1.0);
      const Point d = position(i) - (s.a + reach * along);
      const double distance = d.norm();
      if (distance < radius_[i] && distance > 0) {
        position(i) += (radius_[i] - distance) / distance * d;
        ++counters_.position_corrections;
      }
    }
  }
}

template <int D>
void BallCollisions<D>::find_wall_events(int i, double t) {
  const int walls = static_cast<int>(planes_.size() + segments_.size());
  for (int w = 0; w < walls; ++w) {
    const double toi = wall_impact(i, w, t, nullptr);
    if (toi != kNoImpact) push(t + toi, i, -1 - w);
  }
}

template <int D>
void BallCollisions<D>::find_events(int i, double t, int exclude) {
  find_wall_events(i, t);
  if (radius_[i] <= 0 || balls_.size() < 2) return;
  if (!fast_flag_[i]) {
    // Its possible partners started in the neighbouring cells, or are fast.
    const Cell& c = ball_cell_[i];
    Point low, high;
    for (int k = 0; k < D; ++k) {
      low[k] = origin_[k] + (c[k] - 1 + 0.5) * cell_size_;
      high[k] = origin_[k] + (c[k] + 1 + 0.5) * cell_size_;
    }
    for_cells_in_box(low, high, [&](int k) {
      if (k != i && k != exclude && !fast_flag_[k]) test_pair(i, k, t);
    });
  } else {
    // A fast ball's partners started anywhere near its remaining path.
    const Point p = position_at(i, t), q = p + velocity(i) * (h_ - t);
    const double margin = radius_[i] + max_radius_ + sweep_;
    for_cells_in_box(p.cwiseMin(q).array() - margin, p.cwiseMax(q).array() + margin, [&](int k) {
      if (k != i && k != exclude && !fast_flag_[k]) test_pair(i, k, t);
    });
  }
  for (int k : fast_)
    if (k != i && k != exclude) test_pair(i, k, t);
}

template <int D>
double BallCollisions<D>::wall_impact(int i, int w, double t, Point* normal) {
  const Point p = position_at(i, t);
  const Point u = velocity(i);
  const double r = radius_[i];
  const double horizon = h_ - t;
  if (w < static_cast<int>(planes_.size())) {
    const Plane& plane = planes_[w];
    if (normal) *normal = plane.normal;
    return sphere_plane_impact(plane.normal.dot(p) - plane.offset - r, plane.normal.dot(u), horizon);
  }
  if constexpr (D == 2) {
    // A segment is a capsule of radius r around it for the ball's centre: its two sides
    // (lines) and its two round ends (points).
    const Segment& s = segments_[static_cast<size_t>(w) - planes_.size()];
    const Point along = s.b - s.a;
    const double length = along.norm();
    const Point tangent = along / length;
    const Point side(-tangent[1], tangent[0]);
    double best = kNoImpact;
    Point best_normal = side;
    const double offset = side.dot(p - s.a);
    const double sign = offset > 0 || (offset == 0 && side.dot(u) < 0) ? 1 : -1;
    const double toi = sphere_plane_impact(sign * offset - r, sign * side.dot(u), horizon);
    if (toi != kNoImpact) {
      const double reach = tangent.dot(p + u * toi - s.a);
      if (reach >= 0 && reach <= length) {
        best = toi;
        best_normal = sign * side;
      }
    }
    for (const Point* end : {&s.a, &s.b}) {
      const Point d = p - *end;
      const double te = sphere_sphere_impact(d.squaredNorm(), d.dot(u), u.squaredNorm(), r, horizon);
      if (te < best) {
        best = te;
        best_normal = (p + u * te - *end).normalized();
      }
    }
    if (normal) *normal = best_normal;
    return best;
  } else {
    return kNoImpact;
  }
}

template <int D>
void BallCollisions<D>::mark_fast_if_needed(int i, double t) {
  if (fast_flag_[i] || radius_[i] <= 0) return;
  if (travelled_[i] + velocity(i).norm() * (h_ - t) > sweep_) {
    fast_flag_[i] = 1;
    fast_.push_back(i);
  }
}

template <int D>
void BallCollisions<D>::resolve(const Event& e) {
  const int i = e.i;
  advance(i, e.t);
  if (e.other >= 0) {
    const int k = e.other;
    advance(k, e.t);
    const Point d = position(k) - position(i);
    const double distance = d.norm();
    if (distance > 0) {
      double restitution = restitution_[i] * restitution_[k];
      if (restitution < 1 && (collisions_this_step_[i] > kCollapseLimit || collisions_this_step_[k] > kCollapseLimit))
        restitution = 0;
      collide_balls(velocity(i), velocity(k), inverse_mass_[i], inverse_mass_[k], Point(d / distance), restitution);
    }
    ++collision_count_[i];
    ++collision_count_[k];
    ++collisions_this_step_[i];
    ++collisions_this_step_[k];
    ++counters_.ball_collisions;
    mark_fast_if_needed(i, e.t);
    mark_fast_if_needed(k, e.t);
    find_events(i, e.t, k);
    find_events(k, e.t, i);
  } else {
    Point n;
    wall_impact(i, -1 - e.other, e.t, &n);  // the normal at the contact
    const int w = -1 - e.other;
    const double wall_e = w < static_cast<int>(planes_.size()) ? planes_[w].restitution
                                                               : segments_[static_cast<size_t>(w) - planes_.size()].restitution;
    double restitution = restitution_[i] * wall_e;
    if (restitution < 1 && collisions_this_step_[i] > kCollapseLimit) restitution = 0;
    bounce_off_wall(velocity(i), n, restitution);
    ++collision_count_[i];
    ++collisions_this_step_[i];
    ++counters_.wall_collisions;
    mark_fast_if_needed(i, e.t);
    find_events(i, e.t, -1);
  }
}

template class BallCollisions<1>;
template class BallCollisions<2>;
template class BallCollisions<3>;

}  // namespace motus
