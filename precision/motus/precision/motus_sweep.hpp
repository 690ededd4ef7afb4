#pragma once
// motus's own integrators (and a plug-in's) swept over step sizes or tolerances on a scene with an
// exact solution or reference states: one Curve per method (work_precision.hpp).
#include "motus/integrate/method.hpp"
#include "motus/precision/work_precision.hpp"
#include "motus/scene.hpp"
#include "motus/vector.hpp"

namespace motus::precision {

// The exact (or reference) state at t; InputError-like std::invalid_argument naming the scene when
// there is none at that time.
Vector true_state(const SceneDescription& scene, double t);

// Max over the state of |y − y_exact| at t (inf when not finite).
double state_error(const SceneDescription& scene, const Vector& y, double t);

// One curve: fixed-step methods at Sweep::fixed_steps, adaptive ones at Sweep::tolerances. A method
// that cannot run the scene (symplectic on a first-order system) comes back with `unsupported` set
// and no points; a run that fails (a step size underflowing) is a point with `failed` set.
Curve sweep_motus(const SceneDescription& scene, const Method& method, const Sweep& sweep);
// Why motus's `method` cannot run `scene` (a symplectic method on a first-order system, collisions
// or sticks it has no pass for), or "" when it can: the curve's `unsupported`.
std::string why_motus_cannot_run(const SceneDescription& scene, const Method& method);

}  // namespace motus::precision
