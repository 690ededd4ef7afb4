#include "motus/world.hpp"

#include <algorithm>
#include <atomic>

#include "motus/scene_error.hpp"

namespace motus {
namespace {

// The start's projections (World::project_at_start) sweep at most this many times in all, and make
// at most about this many tests (of a stick, or of a body and the walls and a few balls) in all: a
// start the constraints can all hold is still long before (measured, with 10 sweeps a projection:
// three balls of r = 0.5 m in a row 0.1 m into each other, pushed into a wall, in 10 projections; a
// row of 20 in 362; 400 balls on a square lattice 0.1 m into each other, in a corner of their box,
// in 854, 0.1 s), one they cannot would go on for ever (2,500 balls on a lattice of 0.79 m in a box
// of 40 m: stopped by the tests in 0.85 s; six in a box 5 m wide find a fixed point, overlapping,
// in 10 projections).
constexpr int kStartSweeps = 100'000;
constexpr double kStartWork = 4e7;
// A projection that moves no coordinate by more than this fraction of the positions' size (or of
// the largest ball) moved it by rounding: the start has nothing left to move.
constexpr double kStartRounding = 1e-12;

MechanicalSystem make_system(const MechanicalDescription& scene) {
  std::vector<double> masses;
  for (const auto& b : scene.bodies) masses.push_back(b.mass);
  return MechanicalSystem(scene.dimensions, masses, scene.forces);
}

}  // namespace

World::World(const MechanicalDescription& scene, const Method& method, ExternalParts parts)
    : system_(make_system(scene)), has_forces_(scene.forces.acts()),
      has_sticks_(!scene.sticks.empty()) {
  const ForceSet& f = scene.forces;
  position_dependent_forces_ =
      !f.springs.empty() || !f.central_gravity.empty() || !f.mutual_gravity.empty() || !f.pendulums.empty();
  std::vector<double> radius, restitution;
  int balls = 0;
  for (const auto& b : scene.bodies) {
    radius.push_back(b.radius);
    restitution.push_back(b.restitution);
    balls += b.radius > 0;
    largest_radius_ = std::max(largest_radius_, b.radius);
  }
  const bool contacts = !scene.colliders.empty() || balls >= 2;
  const bool constrained = !scene.sticks.empty() || !scene.pins.empty();
  const std::string name = method.name();
  const bool verlet = !method.is_external() && method.builtin() == Integrator::Verlet;
  const bool symplectic_euler = !method.is_external() && method.builtin() == Integrator::SymplecticEuler;

  if (constrained || (contacts && verlet)) {
    if (!verlet)
      throw SceneError("integrator", name +
                                         " cannot run sticks and pins: they are projected on velocityless Verlet; "
                                         "use verlet");
    substeps_ = scene.constraint_substeps;
    if (substeps_ < 1)
      throw SceneError("constraint_substeps", "must be at least 1 (" + std::to_string(substeps_) + " given)");
    // One projection per step sweeps in the scene's order (Jakobsen's sweep, to the last bit);
    // substeps sweep in colours, whose error falls with the substeps where the scene's order's
    // does not (docs/course.md, section 10).
    const SweepOrder order = substeps_ > 1 ? SweepOrder::colours : SweepOrder::scene;
    Vector inverse_mass = system_.masses().cwiseInverse();
    constraints_ = std::make_unique<ConstraintProjection>(scene.dimensions, inverse_mass, radius, scene.sticks,
                                                          scene.pins, scene.colliders, scene.constraint_iterations, order);
    project_contacts_ = contacts;
    // (A sweep's tests: each stick, and each body against the walls and a few balls.)
    const double sweep_tests = static_cast<double>(scene.sticks.size()) +
                               static_cast<double>(scene.bodies.size()) *
                                   static_cast<double>(constraints_->walls().size() + scene.colliders.segments.size() + 4);
    start_projections_ = static_cast<int>(std::clamp(
        std::min<double>(kStartSweeps, kStartWork / sweep_tests) / scene.constraint_iterations, 1.0, double{kStartSweeps}));
    ignores_restitution_ = contacts && std::any_of(restitution.begin(), restitution.end(), [](double e) { return e > 0; });
    velocity_dependent_forces_ = !f.drag.empty() || !f.springs.empty();
    if (parts.constraints) use_external_projection(scene, *parts.constraints);
    return;
  }
  if (contacts) {
    if (!symplectic_euler)
      throw SceneError("integrator", name +
                                         " cannot run collisions: contacts are resolved at their time of impact during "
                                         "symplectic Euler's drift (symplectic-euler) or projected (verlet)");
    const Vector inverse_mass = system_.masses().cwiseInverse();
    external_collisions_ = parts.collisions != nullptr;
    switch (scene.dimensions) {
      case 1: collisions_.emplace<BallCollisions<1>>(inverse_mass, radius, restitution, scene.colliders, parts.collisions); break;
      case 2: collisions_.emplace<BallCollisions<2>>(inverse_mass, radius, restitution, scene.colliders, parts.collisions); break;
      default: collisions_.emplace<BallCollisions<3>>(inverse_mass, radius, restitution, scene.colliders, parts.collisions); break;
    }
  }
}

void World::use_external_projection(const MechanicalDescription& scene, const ExternalConstraintRules& rules) {
  if (!scene.colliders.segments.empty())
    throw SceneError("colliders", "a constraint projection from a plug-in handles planes and boxes, not segments");
  external_projection_ = &rules;
  for (const auto& b : scene.bodies) {
    external_inverse_mass_.push_back(1 / b.mass);
    external_radius_.push_back(b.radius);
  }
  for (const auto& s : scene.sticks) external_sticks_.push_back({s.a, s.b, s.length});
  for (const auto& p : scene.pins) external_pins_.push_back({p.body, {p.position[0], p.position[1], p.position[2]}});
  for (const auto& w : constraints_->walls()) external_walls_.push_back({{w.normal[0], w.normal[1], w.normal[2]}, w.offset});
  static std::atomic<long> runs{0};
  external_set_ = {++runs,
                   scene.dimensions,
                   static_cast<int>(scene.bodies.size()),
                   external_inverse_mass_.data(),
                   external_radius_.data(),
                   static_cast<int>(external_sticks_.size()),
                   external_sticks_.data(),
                   static_cast<int>(external_pins_.size()),
                   external_pins_.data(),
                   static_cast<int>(external_walls_.size()),
                   external_walls_.data(),
                   scene.constraint_iterations};
}

void World::project(VectorRef x) {
  if (!external_projection_) {
    constraints_->project(x);
    return;
  }
  // Balls against each other are motus's to keep apart (the outside projection does not see
  // them), first, so that the outside projection's walls and pins have the last word.
  constraints_->push_balls_apart(x);
  check_external(external_projection_->project(external_projection_->self, &external_set_, x.data()),
                 "constraint projection", external_projection_->error, external_projection_->self);
}

// The start: projections until one moves nothing but by rounding (or start_projections_ of them),
// positions only (Verlet takes its previous positions from these and the velocities). One
// projection's sweeps leave part of what they move (Jakobsen's relaxation: each constraint put
// right breaks its neighbours a little), a wall pushing back what a pair pushed into it, and
// what the start left, the first step's projection moved, read by Verlet as velocity. A start
// with nothing to move (every shipped scene) is one projection, as before.
void World::project_at_start(VectorRef x) {
  if (x.size() == 0) return project(x);  // (no bodies: nothing to measure)
  Vector before;
  for (int p = 0; p < start_projections_; ++p) {
    before = x;
    project(x);
    const double rounding = kStartRounding * std::max(x.cwiseAbs().maxCoeff(), largest_radius_);
    // (A NaN stops it: no projection will put that right.)
    if (!((x - before).cwiseAbs().maxCoeff() > rounding)) break;
  }
}

void World::drift_with_collisions(VectorRef x, VectorRef v, double h, bool kicked) {
  std::visit(
      [&](auto& c) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(c)>, std::monostate>) c.drift(x, v, h, kicked);
      },
      collisions_);
}

std::vector<std::string> World::passes() const {
  std::vector<std::string> p;
  if (has_forces_) p.push_back("forces");
  p.push_back("drift");
  // (A plug-in's part is named as such: what runs is then the student's code, not motus's.)
  if (has_collisions())
    p.push_back(external_collisions_ ? "collisions (the plug-in's impulses and times of impact)"
                                     : "collisions (impulses at the time of impact)");
  if (constraints_) {
    const std::string what = project_contacts_ ? "constraints and contacts" : "constraints";
    p.push_back(what + (external_projection_ ? " (the plug-in's projection)" : " (projection)"));
  }
  return p;
}

CollisionCounters World::collision_counters() const {
  CollisionCounters counters;
  std::visit(
      [&](const auto& c) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(c)>, std::monostate>) counters = c.counters();
      },
      collisions_);
  if (constraints_) counters.cell_queries += constraints_->broad_phase_queries();
  return counters;
}

double World::constraint_error(ConstVectorRef x) const {
  return has_sticks_ ? constraints_->max_relative_stick_error(x) : 0.0;
}

double World::pin_error(ConstVectorRef x) const { return has_pins() ? constraints_->max_pin_distance(x) : 0.0; }

}  // namespace motus
