#pragma once
// Box2D 2.4 and Bullet 3 on the same scene, through compare's backends (the fair settings of
// docs/peers.md), at the steps games use: dt = 1/30 … 1/960 s (engine_steps()). Both integrate with
// semi-implicit (symplectic) Euler, so on a diagram their lines lie along motus's
// symplectic-euler: error ∝ dt, one force evaluation per step. Only the steps are timed.
#include <string>

#include "motus/precision/work_precision.hpp"
#include "motus/scene.hpp"

namespace motus::precision {

// name: "box2d" or "bullet". A scene the engine cannot run (Box2D: 1-D and 3-D scenes) comes back
// with `unsupported` set to the backend's reasons, one line.
Curve sweep_engine(const SceneDescription& scene, const std::string& name, const Sweep& sweep);

}  // namespace motus::precision
