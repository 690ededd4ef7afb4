#pragma once
// The analytic solutions and reference states a scene can declare, for checking
// accuracy (`motus bench precision`, the tests):
//   "exact": "harmonic"        one body, one zero-length spring to an anchor, optional damping
//   "exact": "kepler"          one body in 2-D around one fixed centre of inverse-square gravity
//   "exact": "pendulum"        one pendulum body started at θ = 0
//   "exact": "projectile-drag" bodies under uniform gravity and linear drag on every body
//   "exact": "free-flight"     balls under uniform gravity (or none) in true collisions with each
//                              other and with planes and boxes, event by event (free_flight.hpp)
//   "reference": [{"t": ..., "state": [...]}, ...]   states known to high accuracy
#include <optional>

#include "motus/scene.hpp"
#include "motus/vector.hpp"

namespace motus {

// Names of the analytic solutions, for error messages and the scene format.
const char* exact_solution_names();

// Throws SceneError("exact", ...) when the scene is not the problem its declared
// solution solves.
void check_exact_solution(const SceneDescription& scene);

// The true state at time t — [x; v] for a mechanical scene, y for a first-order one —
// from the scene's analytic solution, or from a reference state at t (within 1e-9).
std::optional<Vector> exact_state(const SceneDescription& scene, double t);

// The last time at which exact_state is known, if it is only known at reference
// times (a reference-only scene); otherwise nullopt (known at every time).
std::optional<double> last_reference_time(const SceneDescription& scene);

bool has_exact_solution(const SceneDescription& scene);

}  // namespace motus
