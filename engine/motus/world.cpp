#include "motus/world.hpp"

#include "motus/scene_error.hpp"

namespace motus {
namespace {

MechanicalSystem make_system(const MechanicalDescription& scene) {
  std::vector<double> masses;
  for (const auto& b : scene.bodies) masses.push_back(b.mass);
  return MechanicalSystem(scene.dimensions, masses, scene.forces);
}

}  // namespace

World::World(const MechanicalDescription& scene, Integrator integrator)
    : system_(make_system(scene)), integrator_(integrator), has_forces_(!scene.forces.empty()),
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
  }
  const bool contacts = !scene.colliders.empty() || balls >= 2;
  const bool constrained = !scene.sticks.empty() || !scene.pins.empty();
  const char* name = info(integrator).name;

  if (constrained || (contacts && integrator == Integrator::Verlet)) {
    if (integrator != Integrator::Verlet)
      throw SceneError("integrator", std::string(name) +
                                         " cannot run sticks and pins: they are projected on velocityless Verlet; "
                                         "use verlet");
    Vector inverse_mass = system_.masses().cwiseInverse();
    constraints_ = std::make_unique<ConstraintProjection>(scene.dimensions, inverse_mass, radius, scene.sticks,
                                                          scene.pins, scene.colliders, scene.constraint_iterations);
    project_contacts_ = contacts;
    return;
  }
  if (contacts) {
    if (integrator != Integrator::SymplecticEuler)
      throw SceneError("integrator", std::string(name) +
                                         " cannot run collisions: contacts are resolved at their time of impact during "
                                         "symplectic Euler's drift (symplectic-euler) or projected (verlet)");
    const Vector inverse_mass = system_.masses().cwiseInverse();
    switch (scene.dimensions) {
      case 1: collisions_.emplace<BallCollisions<1>>(inverse_mass, radius, restitution, scene.colliders); break;
      case 2: collisions_.emplace<BallCollisions<2>>(inverse_mass, radius, restitution, scene.colliders); break;
      default: collisions_.emplace<BallCollisions<3>>(inverse_mass, radius, restitution, scene.colliders); break;
    }
  }
}

void World::drift_with_collisions(VectorRef x, VectorRef v, double h) {
  std::visit(
      [&](auto& c) {
        if constexpr (!std::is_same_v<std::decay_t<decltype(c)>, std::monostate>) c.drift(x, v, h);
      },
      collisions_);
}

std::vector<std::string> World::passes() const {
  std::vector<std::string> p;
  if (has_forces_) p.push_back("forces");
  p.push_back("drift");
  if (has_collisions()) p.push_back("collisions (impulses at the time of impact)");
  if (constraints_) p.push_back(project_contacts_ ? "constraints and contacts (projection)" : "constraints (projection)");
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

}  // namespace motus
