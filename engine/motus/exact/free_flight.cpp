#include "motus/exact/free_flight.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "motus/scene_error.hpp"

namespace motus {
namespace {

[[noreturn]] void unfit(const std::string& why) { throw SceneError("exact", "\"free-flight\" " + why); }

constexpr double kNever = std::numeric_limits<double>::infinity();
// Touching, to rounding: the gap that counts as contact, relative to the contact distance.
constexpr double kTouching = 1e-12;
// A bounce lower than this (m) means the ball has come to rest on the wall.
constexpr double kRestingHop = 1e-12;

struct Wall {  // the free side is n·x ≥ offset; n is a unit vector
  double n[3];
  double offset, restitution;
};

struct World {
  int d = 2, bodies = 0;
  std::vector<double> x, v, mass, radius, restitution;
  double g[3] = {0, 0, 0};
  std::vector<Wall> walls;

  double dot(const double* a, const double* b) const {
    double s = 0;
    for (int k = 0; k < d; ++k) s += a[k] * b[k];
    return s;
  }
  const double* x_of(int i) const { return &x[static_cast<size_t>(i * d)]; }
  const double* v_of(int i) const { return &v[static_cast<size_t>(i * d)]; }
  double height(int i, const Wall& w) const { return dot(w.n, x_of(i)) - w.offset - radius[static_cast<size_t>(i)]; }
};

World world_of(const MechanicalDescription& m) {
  World w;
  w.d = m.dimensions;
  w.bodies = static_cast<int>(m.bodies.size());
  for (const auto& b : m.bodies) {
    for (int k = 0; k < w.d; ++k) {
      w.x.push_back(b.position[static_cast<size_t>(k)]);
      w.v.push_back(b.velocity.empty() ? 0.0 : b.velocity[static_cast<size_t>(k)]);
    }
    w.mass.push_back(b.mass);
    w.radius.push_back(b.radius);
    w.restitution.push_back(b.restitution);
  }
  for (const auto& g : m.forces.gravity)
    for (int k = 0; k < w.d; ++k) w.g[k] += g.g[static_cast<size_t>(k)];
  for (const auto& p : m.colliders.planes) {
    double length = 0;
    for (int k = 0; k < w.d; ++k) length += p.normal[static_cast<size_t>(k)] * p.normal[static_cast<size_t>(k)];
    length = std::sqrt(length);
    Wall wall{{0, 0, 0}, p.offset / length, p.restitution};
    for (int k = 0; k < w.d; ++k) wall.n[k] = p.normal[static_cast<size_t>(k)] / length;
    w.walls.push_back(wall);
  }
  for (const auto& b : m.colliders.boxes)
    for (int k = 0; k < w.d; ++k) {
      Wall low{{0, 0, 0}, b.min[static_cast<size_t>(k)], b.restitution}, high{{0, 0, 0}, -b.max[static_cast<size_t>(k)], b.restitution};
      low.n[k] = 1;
      high.n[k] = -1;
      w.walls.push_back(low);
      w.walls.push_back(high);
    }
  return w;
}

// When balls i and j next touch while approaching (kNever: they do not). Relative motion is a
// straight line, since gravity moves both alike: |r + u τ|² = R², i.e. a τ² + 2 b τ + c = 0.
double pair_contact(const World& w, int i, int j) {
  double r[3], u[3];
  for (int k = 0; k < w.d; ++k) {
    r[k] = w.x_of(j)[k] - w.x_of(i)[k];
    u[k] = w.v_of(j)[k] - w.v_of(i)[k];
  }
  const double R = w.radius[static_cast<size_t>(i)] + w.radius[static_cast<size_t>(j)];
  const double a = w.dot(u, u), b = w.dot(r, u), c = w.dot(r, r) - R * R;
  if (!(b < 0)) return kNever;          // separating, or sliding past
  if (c <= kTouching * R * R) return 0;  // touching (or overlapped by rounding) and approaching
  const double disc = b * b - a * c;
  if (disc < 0) return kNever;  // they miss
  return c / (-b + std::sqrt(disc));  // the smaller root, in the form that does not cancel
}

// When ball i next comes down onto wall w: f(τ) = c + b τ + ½ a τ² = 0 with f′(τ) < 0.
double wall_contact(const World& w, int i, const Wall& wall) {
  const double c = w.height(i, wall), b = w.dot(wall.n, w.v_of(i)), a = w.dot(wall.n, w.g);
  const double touching = kTouching * std::max(1.0, w.radius[static_cast<size_t>(i)]);
  // Touching and approaching, or touching at rest with gravity pulling it in (a ball set down on the
  // floor: without this it fell through, ½ g t² below, and every engine was blamed for holding it).
  if (c <= touching && (b < 0 || (b == 0 && a < 0))) return 0;
  if (a == 0) return b < 0 ? std::max(0.0, -c / b) : kNever;
  const double disc = b * b - 2 * a * c;
  if (disc < 0) return kNever;
  const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  double best = kNever;
  for (double root : {2 * q / a, q != 0 ? c / q : kNever})
    if (std::isfinite(root) && root >= 0 && b + a * root < 0) best = std::min(best, root);
  return best;
}

void advance(World& w, double tau) {
  for (int i = 0; i < w.bodies; ++i)
    for (int k = 0; k < w.d; ++k) {
      const size_t at = static_cast<size_t>(i * w.d + k);
      w.x[at] += w.v[at] * tau + 0.5 * w.g[k] * tau * tau;
      w.v[at] += w.g[k] * tau;
    }
}

// The impulse along the line of centres: momentum kept, the normal approach speed reversed
// and scaled by e.
void collide(World& w, int i, int j) {
  double n[3], distance = 0;
  for (int k = 0; k < w.d; ++k) {
    n[k] = w.x_of(j)[k] - w.x_of(i)[k];
    distance += n[k] * n[k];
  }
  distance = std::sqrt(distance);
  for (int k = 0; k < w.d; ++k) n[k] /= distance;
  double approach = 0;
  for (int k = 0; k < w.d; ++k) approach += (w.v_of(j)[k] - w.v_of(i)[k]) * n[k];
  const double e = w.restitution[static_cast<size_t>(i)] * w.restitution[static_cast<size_t>(j)];
  const double mi = w.mass[static_cast<size_t>(i)], mj = w.mass[static_cast<size_t>(j)];
  const double J = -(1 + e) * approach / (1 / mi + 1 / mj);
  for (int k = 0; k < w.d; ++k) {
    w.v[static_cast<size_t>(i * w.d + k)] -= J / mi * n[k];
    w.v[static_cast<size_t>(j * w.d + k)] += J / mj * n[k];
  }
}

// Bounces ball i off the wall; false when it has come to rest on it (under gravity).
bool bounce(World& w, int i, const Wall& wall) {
  const double e = w.restitution[static_cast<size_t>(i)] * wall.restitution;
  const double normal = w.dot(wall.n, w.v_of(i)), pull = w.dot(wall.n, w.g);
  for (int k = 0; k < w.d; ++k) w.v[static_cast<size_t>(i * w.d + k)] -= (1 + e) * normal * wall.n[k];
  const double up = -e * normal;  // the speed it leaves with
  return !(pull < 0 && up * up < 2 * -pull * kRestingHop);
}

}  // namespace

void check_free_flight(const SceneDescription& scene) {
  const auto& m = *scene.mechanical;
  const auto& f = m.forces;
  if (!f.springs.empty() || !f.drag.empty() || !f.central_gravity.empty() || !f.mutual_gravity.empty() ||
      !f.pendulums.empty())
    unfit("needs bodies in free flight: uniform gravity is the only force it solves");
  if (!m.sticks.empty() || !m.pins.empty()) unfit("solves free balls: no sticks or pins");
  if (!m.colliders.segments.empty()) unfit("solves walls that are planes or boxes, not segments");
  if (m.bodies.size() > static_cast<size_t>(kFreeFlightMaxBodies))
    unfit("solves up to " + std::to_string(kFreeFlightMaxBodies) + " bodies (this scene has " +
          std::to_string(m.bodies.size()) + ")");
  const World w = world_of(m);
  for (int i = 0; i < w.bodies; ++i) {
    for (const auto& wall : w.walls)
      if (w.height(i, wall) < -kTouching * std::max(1.0, w.radius[static_cast<size_t>(i)]))
        unfit("needs every body clear of the walls at the start: bodies[" + std::to_string(i) + "] is inside one");
    for (int j = i + 1; j < w.bodies; ++j) {
      if (!(w.radius[static_cast<size_t>(i)] > 0 && w.radius[static_cast<size_t>(j)] > 0)) continue;
      const double R = w.radius[static_cast<size_t>(i)] + w.radius[static_cast<size_t>(j)];
      double r2 = 0;
      for (int k = 0; k < w.d; ++k) r2 += (w.x_of(j)[k] - w.x_of(i)[k]) * (w.x_of(j)[k] - w.x_of(i)[k]);
      if (r2 < R * R * (1 - kTouching))
        unfit("needs the balls apart at the start: bodies[" + std::to_string(i) + "] and bodies[" + std::to_string(j) +
              "] overlap");
    }
  }
}

std::optional<Vector> free_flight_state(const SceneDescription& scene, double elapsed) {
  World w = world_of(*scene.mechanical);
  double now = 0;
  for (long events = 0; events <= kFreeFlightMaxEvents; ++events) {
    // The earliest event: a pair (i, j ≥ 0) or a wall (i, j = −1 − wall index).
    double first = kNever;
    int a = -1, b = 0;
    for (int i = 0; i < w.bodies; ++i) {
      if (w.radius[static_cast<size_t>(i)] > 0)
        for (int j = i + 1; j < w.bodies; ++j)
          if (w.radius[static_cast<size_t>(j)] > 0)
            if (const double tau = pair_contact(w, i, j); tau < first) first = tau, a = i, b = j;
      for (size_t k = 0; k < w.walls.size(); ++k)
        if (const double tau = wall_contact(w, i, w.walls[k]); tau < first) first = tau, a = i, b = -1 - static_cast<int>(k);
    }
    if (a < 0 || now + first > elapsed) {
      advance(w, elapsed - now);
      const Eigen::Index n = static_cast<Eigen::Index>(w.x.size());
      Vector y(2 * n);
      for (Eigen::Index k = 0; k < n; ++k) y[k] = w.x[static_cast<size_t>(k)], y[n + k] = w.v[static_cast<size_t>(k)];
      return y;
    }
    advance(w, first);
    now += first;
    if (b >= 0)
      collide(w, a, b);
    else if (!bounce(w, a, w.walls[static_cast<size_t>(-1 - b)]))
      return std::nullopt;  // at rest on a wall: unknown from here on
  }
  return std::nullopt;
}

}  // namespace motus
