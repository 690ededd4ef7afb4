#pragma once
// A mechanical scene's world: point masses and exactly the passes its scene uses,
// stepped in order (Box2D-Lite's World::Step as a recipe):
//   forces       the integrator's kick, a = F/m          — only if the scene has forces
//   drift        straight lines, x += v Δt               — always
//   collisions   the drift stops at every contact and resolves it with an impulse
//                (symplectic-euler), or contacts are projected apart (verlet)
//                                                        — only with walls or two balls
//   constraints  sticks and pins by projection (verlet)  — only with sticks or pins
// A scene without colliders and with fewer than two balls does no collision detection;
// one without sticks, pins or contacts never projects; with collisions and no forces, the kick
// is skipped. (Without any pass the integrator steps the system as it is; an empty force
// set costs it a zeroed array.)
#include <memory>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "motus/collide/ball_collisions.hpp"
#include "motus/constrain/constraint_projection.hpp"
#include "motus/external/external_parts.hpp"
#include "motus/integrate/symplectic_euler.hpp"
#include "motus/integrate/verlet.hpp"
#include "motus/integrate/method.hpp"
#include "motus/scene.hpp"
#include "motus/systems/mechanical_system.hpp"

namespace motus {

class World {
public:
  // Throws SceneError("integrator", ...) when the integrator cannot run this scene's passes.
  // `parts` replace the collision response or the constraint projection (a plug-in's).
  World(const MechanicalDescription& scene, const Method& method, ExternalParts parts = {});

  MechanicalSystem& system() { return system_; }
  const MechanicalSystem& system() const { return system_; }

  bool has_collisions() const { return !std::holds_alternative<std::monostate>(collisions_); }
  // Whether it projects positions (sticks, pins, or verlet's contacts): not only with sticks.
  bool has_constraints() const { return constraints_ != nullptr; }
  bool has_sticks() const { return has_sticks_; }
  // Whether it projects contacts apart (verlet) where a body's restitution asks for a bounce: the
  // projection has no velocity to reverse, so restitution is not used (run and compare say so).
  bool ignores_restitution() const { return ignores_restitution_; }
  // The passes this world runs, in order (for summaries and reports).
  std::vector<std::string> passes() const;

  // One step of h from (x, v) at time t with the scene's integrator. (Always inlined into
  // the run loop: bench_collisions holds it to 1.10x of the bare integrator.)
  template <class Stepper>
  [[gnu::always_inline]] void step(Stepper& stepper, double t, double h, VectorRef x, VectorRef v);

  // Counted work: all zero when the scene has no collision pass.
  CollisionCounters collision_counters() const;
  // The largest relative stick-length error now (0 without sticks).
  double constraint_error(ConstVectorRef x) const;
  // The farthest a pinned body is from its pin now (0 without pins).
  bool has_pins() const { return constraints_ && constraints_->has_pins(); }
  double pin_error(ConstVectorRef x) const;

private:
  void drift_with_collisions(VectorRef x, VectorRef v, double h, bool kicked);
  void project(VectorRef x);
  void project_at_start(VectorRef x);
  void use_external_projection(const MechanicalDescription& scene, const ExternalConstraintRules& rules);

  MechanicalSystem system_;
  bool has_forces_;
  std::variant<std::monostate, BallCollisions<1>, BallCollisions<2>, BallCollisions<3>> collisions_;
  std::unique_ptr<ConstraintProjection> constraints_;
  bool project_contacts_ = false;  // verlet: walls and balls are projection constraints too
  bool ignores_restitution_ = false;  // ... and some body's e > 0
  bool has_sticks_ = false;
  bool external_collisions_ = false;  // a plug-in's collision rules resolve the contacts
  int substeps_ = 1;  // Verlet steps per step with a projection (the scene's constraint_substeps)
  int start_projections_ = 1;  // the most the start may take (project_at_start)
  double largest_radius_ = 0;  // (the start's rounding: project_at_start)
  bool position_dependent_forces_ = false;  // anything but uniform gravity and drag
  bool velocity_dependent_forces_ = false;  // drag, springs (any spring: it may be damped)

  // A projection from outside (ExternalParts::constraints): the rules and the set they are
  // given, whose arrays live here for the whole run. It moves sticks, pins and walls; motus
  // still pushes balls apart, before it.
  const ExternalConstraintRules* external_projection_ = nullptr;
  ExternalConstraintSet external_set_{};
  std::vector<double> external_inverse_mass_, external_radius_;
  std::vector<ExternalStick> external_sticks_;
  std::vector<ExternalPin> external_pins_;
  std::vector<ExternalWall> external_walls_;
};

template <class Stepper>
inline void World::step(Stepper& stepper, double t, double h, VectorRef x, VectorRef v) {
  if constexpr (std::is_same_v<Stepper, SymplecticEuler>) {
    if (has_collisions()) {
      if (has_forces_) stepper.kick(system_, t, h, x, v);
      drift_with_collisions(x, v, h, has_forces_);
      return;
    }
  }
  if constexpr (std::is_same_v<Stepper, Verlet>) {
    if (constraints_) {
      // `substeps_` Verlet steps of h/n, each followed by its projection (Macklin et al.,
      // "Small Steps in Physics Simulation", 2019): the constraint error a free step makes
      // grows as its length squared, so n small steps leave far less than one step with n
      // times the sweeps (docs/course.md, section 10).
      const double hs = h / substeps_;
      // The start projected before the first step, as symplectic Euler moves an overlap apart at
      // the start of a step: positions only. After it, a body set outside its box (or into
      // another ball) was moved in by the first step's projection, and Verlet read that move as
      // its velocity (100 m in one step of 0.01 s: 9950 m/s, 4.95e7 J from nothing). Projected
      // until nothing is left to move (project_at_start), not once: what one projection's sweeps
      // leave of an overlap, the first step moved, and Verlet read that too (three balls at rest
      // in a row, 0.1 m into each other beside a wall: 0.784 J from nothing).
      if (!stepper.started()) project_at_start(x);
      for (int s = 0; s < substeps_; ++s) {
        const double ts = s == 0 ? t : t + s * hs;
        // The positions only: the velocity Verlet would report is replaced below, and a_{n+1}
        // is taken where it can change — before the projection for a drag alone (with the
        // velocity of the substep before, as Verlet's step takes it), after it for forces that
        // read positions — and never for uniform gravity alone, which gives the same a every
        // time (a cloth's 32 substeps a step evaluated it 32 times: 13 % of its step).
        stepper.move(system_, ts, hs, x, v);
        if (velocity_dependent_forces_ && !position_dependent_forces_)
          stepper.refresh_acceleration(system_, ts + hs, x, v);
        project(x);
        // The velocity the positions imply, for the step's end, and between substeps for forces
        // that read it: the backward difference, not Verlet's central one (verlet.hpp), whose
        // ½ h a would give a body resting on a floor or hanging from a pin a velocity of ½ h g
        // (the projection, not a, holds it). A body in free flight here lags by that much.
        if (s + 1 == substeps_ || velocity_dependent_forces_) v = (x - stepper.previous_positions()) / hs;
        // Forces that depend on position must see where the projection put the bodies.
        if (position_dependent_forces_) stepper.refresh_acceleration(system_, ts + hs, x, v);
      }
      return;
    }
  }
  stepper.step(system_, t, h, x, v);
}

}  // namespace motus
