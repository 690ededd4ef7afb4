#include "motus/compare/metrics.hpp"

#include <algorithm>
#include <cmath>

#include "motus/exact/exact_solution.hpp"

namespace motus::compare {
namespace {

MechanicalSystem system_of(const SceneDescription& scene) {
  std::vector<double> masses;
  for (const auto& b : scene.mechanical->bodies) masses.push_back(b.mass);
  return MechanicalSystem(scene.mechanical->dimensions, masses, scene.mechanical->forces);
}

}  // namespace

Metrics::Metrics(const SceneDescription& scene)
    : scene_(scene), system_(system_of(scene)), d_(scene.mechanical->dimensions) {
  for (size_t i = 0; i < scene.mechanical->bodies.size(); ++i) {
    radius_.push_back(scene.mechanical->bodies[i].radius);
    max_radius_ = std::max(max_radius_, radius_.back());
    if (radius_.back() > 0) balls_.push_back(static_cast<int>(i));
  }
}

MetricsRow Metrics::measure(const Snapshot& s, const Snapshot* motus) const {
  const Eigen::Map<const Vector> x(s.x.data(), static_cast<Eigen::Index>(s.x.size()));
  const Eigen::Map<const Vector> v(s.v.data(), static_cast<Eigen::Index>(s.v.size()));
  MetricsRow row;
  row.t = s.t;
  row.kinetic = system_.kinetic_energy(v);
  row.potential = system_.potential_energy(x);
  row.total = row.kinetic + row.potential;
  const Vector p = system_.momentum(v), l = system_.angular_momentum(x, v);
  row.momentum.assign(p.data(), p.data() + p.size());
  row.angular_momentum.assign(l.data(), l.data() + l.size());
  row.penetration = deepest_penetration(s.x);

  row.constraint_error = stick_error(s);
  auto farthest = [&](const Vector& other_x) {
    double worst = 0;
    for (Eigen::Index i = 0; i < x.size(); i += d_) worst = worse(worst, (x.segment(i, d_) - other_x.segment(i, d_)).stableNorm());  // (stable: 1e193 m apart is not ∞)
    return worst;
  };
  // (motus against itself: 0, also once its state is not finite, where ∞ − ∞ would read as ∞)
  if (motus == &s) row.from_motus = 0;
  else if (motus) row.from_motus = farthest(Eigen::Map<const Vector>(motus->x.data(), static_cast<Eigen::Index>(motus->x.size())));
  if (has_exact_solution(scene_))
    if (const auto exact = exact_state(scene_, s.t)) row.from_exact = farthest(exact->head(x.size()));
  return row;
}

double Metrics::stick_error(const Snapshot& s) const {
  double worst = 0;
  for (const auto& stick : scene_.mechanical->sticks) {
    double length2 = 0;
    for (int k = 0; k < d_; ++k) {
      const double d = s.x[static_cast<size_t>(stick.a * d_ + k)] - s.x[static_cast<size_t>(stick.b * d_ + k)];
      length2 += d * d;
    }
    worst = worse(worst, std::abs(std::sqrt(length2) - stick.length) / stick.length);
  }
  return worst;
}

bool Metrics::has_contacts() const {
  const Colliders& walls = scene_.mechanical->colliders;
  const bool any_wall = !walls.planes.empty() || !walls.boxes.empty() || !walls.segments.empty();
  return balls_.size() >= 2 || (any_wall && !radius_.empty());
}

double Metrics::deepest_penetration(const std::vector<double>& x) const {
  double deepest = 0;
  const Colliders& walls = scene_.mechanical->colliders;
  auto coordinate = [&](int i, int k) { return x[static_cast<size_t>(i * d_ + k)]; };
  const int n = static_cast<int>(radius_.size());
  for (int i = 0; i < n; ++i) {
    for (const auto& p : walls.planes) {  // the centre's signed distance from the plane, against the radius
      double length = 0, height = -p.offset;
      for (int k = 0; k < d_; ++k) {
        length += p.normal[k] * p.normal[k];
        height += p.normal[k] * coordinate(i, k);
      }
      deepest = worse(deepest, radius_[i] - height / std::sqrt(length));
    }
    for (const auto& b : walls.boxes)
      for (int k = 0; k < d_; ++k) {
        deepest = worse(deepest, radius_[i] - (coordinate(i, k) - b.min[k]));
        deepest = worse(deepest, radius_[i] - (b.max[k] - coordinate(i, k)));
      }
    for (const auto& g : walls.segments) {  // the centre's distance from the segment's nearest point
      double ab2 = 0, ap_ab = 0;
      for (int k = 0; k < d_; ++k) {
        ab2 += (g.b[k] - g.a[k]) * (g.b[k] - g.a[k]);
        ap_ab += (coordinate(i, k) - g.a[k]) * (g.b[k] - g.a[k]);
      }
      const double along = ab2 > 0 ? std::clamp(ap_ab / ab2, 0.0, 1.0) : 0.0;
      double d2 = 0;
      for (int k = 0; k < d_; ++k) {
        const double gap = coordinate(i, k) - (g.a[k] + along * (g.b[k] - g.a[k]));
        d2 += gap * gap;
      }
      deepest = worse(deepest, radius_[i] - std::sqrt(d2));
    }
  }
  if (balls_.size() < 2) return deepest;
  // Balls: sort by a grid cell of size 2·r_max and look at neighbouring cells only.
  const double cell = 2 * max_radius_;
  // A cell index, clamped as a double first: a body a peer has flung to 1e300 m (or to NaN) must
  // not overflow the int (it then shares an edge cell with others, which only costs a comparison).
  auto cell_of = [&](int i, int k) {
    const double c = std::floor(coordinate(i, k) / cell);
    return static_cast<int>(std::clamp(std::isnan(c) ? 0.0 : c, -999999.0, 999999.0));
  };
  auto key = [&](const int* c) {
    long k = 0;
    for (int j = 0; j < d_; ++j) k = k * 2000003L + (c[j] + 1000000L);
    return k;
  };
  cells_.clear();
  for (int i : balls_) {
    int c[3] = {0, 0, 0};
    for (int k = 0; k < d_; ++k) c[k] = cell_of(i, k);
    cells_.emplace_back(key(c), i);
  }
  std::sort(cells_.begin(), cells_.end());
  int offsets = 1;
  for (int k = 0; k < d_; ++k) offsets *= 3;
  for (int i : balls_) {
    int c[3] = {0, 0, 0};
    for (int k = 0; k < d_; ++k) c[k] = cell_of(i, k);
    for (int code = 0; code < offsets; ++code) {
      int n_c[3] = {c[0], c[1], c[2]};
      for (int k = 0, r = code; k < d_; ++k, r /= 3) n_c[k] += r % 3 - 1;
      const long kk = key(n_c);
      for (auto it = std::lower_bound(cells_.begin(), cells_.end(), std::make_pair(kk, -1));
           it != cells_.end() && it->first == kk; ++it) {
        const int j = it->second;
        if (j <= i) continue;
        double d2 = 0;
        for (int k = 0; k < d_; ++k) d2 += (coordinate(i, k) - coordinate(j, k)) * (coordinate(i, k) - coordinate(j, k));
        deepest = worse(deepest, radius_[i] + radius_[j] - std::sqrt(d2));
      }
    }
  }
  return deepest;
}

}  // namespace motus::compare
