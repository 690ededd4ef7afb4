#include "motus/exact/exact_solution.hpp"

#include <cmath>
#include <string>

#include "motus/exact/free_flight.hpp"
#include "motus/exact/harmonic.hpp"
#include "motus/exact/kepler_orbit.hpp"
#include "motus/exact/pendulum_swing.hpp"
#include "motus/exact/projectile_with_drag.hpp"
#include "motus/scene_error.hpp"

namespace motus {
namespace {

[[noreturn]] void unfit(const std::string& why) { throw SceneError("exact", why); }

// The kinds of force a closed form allows (mutual gravity: none of them).
struct Allowed {
  bool gravity = false, springs = false, drag = false, central_gravity = false, pendulums = false;
};

// Whether f has no force of a kind the closed form does not allow.
bool only(const ForceSet& f, Allowed a) {
  return (a.gravity || f.gravity.empty()) && (a.springs || f.springs.empty()) && (a.drag || f.drag.empty()) &&
         (a.central_gravity || f.central_gravity.empty()) && f.mutual_gravity.empty() &&
         (a.pendulums || f.pendulums.empty());
}

// The closed forms of harmonic, kepler, pendulum and projectile-drag know forces alone: a scene with a
// wall, a stick, a pin or two balls that may meet is not the problem they solve, and its "error"
// would be the closed form's, charged to the engine (a pinned harmonic body that never moved was
// 1.9 m from it; a projectile bouncing on a floor, 69 m). free-flight is the solution with walls.
void forces_alone(const MechanicalDescription& m, const std::string& e) {
  if (!m.colliders.empty())
    unfit("\"" + e + "\" solves forces alone, and the scene has colliders (free-flight solves balls among planes and "
          "boxes)");
  if (!m.sticks.empty() || !m.pins.empty())
    unfit("\"" + e + "\" solves forces alone, and the scene has " + (m.sticks.empty() ? "pins" : "sticks"));
  long balls = 0;
  for (const auto& b : m.bodies) balls += b.radius > 0;
  if (balls >= 2)
    unfit("\"" + e + "\" solves forces alone, and " + std::to_string(balls) +
          " of the scene's bodies are balls (a radius above 0) that may meet: give them radius 0");
}

}  // namespace

const char* exact_solution_names() { return "harmonic, kepler, pendulum, projectile-drag, free-flight"; }

void check_exact_solution(const SceneDescription& scene) {
  if (scene.exact.empty()) return;
  const auto& e = scene.exact;
  if (e != "harmonic" && e != "kepler" && e != "pendulum" && e != "projectile-drag" && e != "free-flight")
    unfit("unknown solution \"" + e + "\" (known: " + exact_solution_names() + ")");
  if (!scene.mechanical) unfit("\"" + e + "\" is the solution of a mechanical scene, not of a first-order system");
  const auto& m = *scene.mechanical;
  const ForceSet& f = m.forces;
  if (e != "free-flight") forces_alone(m, e);
  if (e == "harmonic") {
    if (m.bodies.size() != 1 || f.springs.size() != 1 || !only(f, {.springs = true}) ||
        f.springs[0].b != -1 || f.springs[0].rest_length != 0)
      unfit("\"harmonic\" needs one body tied to an anchor by one zero-length spring and no other force");
    const auto& s = f.springs[0];
    const double omega2 = s.stiffness / m.bodies[0].mass, gamma = s.damping / (2 * m.bodies[0].mass);
    if (!(gamma * gamma < omega2)) unfit("\"harmonic\" solves the underdamped spring only (c² < 4km)");
  } else if (e == "kepler") {
    if (m.dimensions != 2 || m.bodies.size() != 1 || f.central_gravity.size() != 1 ||
        !only(f, {.central_gravity = true}) || f.central_gravity[0].softening != 0)
      unfit("\"kepler\" needs one body in 2 dimensions and one unsoftened central gravity, nothing else");
    const auto& b = m.bodies[0];
    const auto& c = f.central_gravity[0];
    const double r = std::hypot(b.position[0] - c.centre[0], b.position[1] - c.centre[1]);
    const double v2 = b.velocity[0] * b.velocity[0] + b.velocity[1] * b.velocity[1];
    if (!(2 / r - v2 / c.mu > 0)) unfit("\"kepler\" solves bound (elliptic) orbits only: this one escapes");
  } else if (e == "pendulum") {
    if (m.dimensions != 1 || m.bodies.size() != 1 || f.pendulums.size() != 1 || !only(f, {.pendulums = true}))
      unfit("\"pendulum\" needs one 1-D body and one pendulum force, nothing else");
    const auto& b = m.bodies[0];
    const auto& p = f.pendulums[0];
    if (b.position[0] != 0) unfit("\"pendulum\" needs the pendulum started at the bottom (bodies[0].position = [0])");
    if (!(std::abs(b.velocity[0]) < 2 * std::sqrt(p.g / p.length)))
      unfit("\"pendulum\" solves swings only: |bodies[0].velocity| must be below 2*sqrt(g/length)");
  } else if (e == "free-flight") {
    check_free_flight(scene);
  } else if (e == "projectile-drag") {
    if (f.gravity.size() != 1 || f.drag.size() != 1 || f.drag[0].body != -1 || !(f.drag[0].coefficient > 0) ||
        !only(f, {.gravity = true, .drag = true}))
      unfit("\"projectile-drag\" needs uniform gravity and one positive linear drag on every body, nothing else");
  }
}

bool has_exact_solution(const SceneDescription& scene) { return !scene.exact.empty() || !scene.reference.empty(); }

std::optional<double> last_reference_time(const SceneDescription& scene) {
  if (!scene.exact.empty() || scene.reference.empty()) return std::nullopt;
  double last = scene.reference.front().t;
  for (const auto& r : scene.reference) last = std::max(last, r.t);
  return last;
}

std::optional<Vector> exact_state(const SceneDescription& scene, double t) {
  if (scene.exact.empty()) {
    for (const auto& r : scene.reference)
      if (std::abs(r.t - t) <= 1e-9 * std::max(1.0, std::abs(t)))
        return Eigen::Map<const Vector>(r.state.data(), static_cast<Eigen::Index>(r.state.size()));
    return std::nullopt;
  }
  const auto& m = *scene.mechanical;
  const int d = m.dimensions;
  const int n = static_cast<int>(m.bodies.size()) * d;
  Vector y(2 * n);
  const double elapsed = t - scene.start_time;
  if (scene.exact == "free-flight") return free_flight_state(scene, elapsed);
  if (scene.exact == "harmonic") {
    const auto& b = m.bodies[0];
    const auto& s = m.forces.springs[0];
    const double omega = std::sqrt(s.stiffness / b.mass), gamma = s.damping / (2 * b.mass);
    for (int k = 0; k < d; ++k) {
      const HarmonicState h = damped_harmonic(b.position[k] - s.anchor[k], b.velocity[k], omega, gamma, elapsed);
      y[k] = s.anchor[k] + h.x;
      y[n + k] = h.v;
    }
  } else if (scene.exact == "kepler") {
    const auto& b = m.bodies[0];
    const auto& c = m.forces.central_gravity[0];
    const KeplerState k = kepler_orbit({b.position[0] - c.centre[0], b.position[1] - c.centre[1]},
                                       {b.velocity[0], b.velocity[1]}, c.mu, elapsed);
    y << k.x[0] + c.centre[0], k.x[1] + c.centre[1], k.v[0], k.v[1];
  } else if (scene.exact == "pendulum") {
    const auto& p = m.forces.pendulums[0];
    const PendulumState s = pendulum_swing(m.bodies[0].velocity[0], p.g / p.length, elapsed);
    y << s.theta, s.omega;
  } else if (scene.exact == "projectile-drag") {
    const auto& g = m.forces.gravity[0];
    const double b = m.forces.drag[0].coefficient;
    for (size_t i = 0; i < m.bodies.size(); ++i)
      for (int k = 0; k < d; ++k) {
        const auto& body = m.bodies[i];
        const ProjectileState s =
            projectile_with_drag(body.position[k], body.velocity[k], g.g[k], body.mass / b, elapsed);
        y[static_cast<Eigen::Index>(i) * d + k] = s.x;
        y[n + static_cast<Eigen::Index>(i) * d + k] = s.v;
      }
  }
  return y;
}

}  // namespace motus
