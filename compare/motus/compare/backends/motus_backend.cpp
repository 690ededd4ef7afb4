#include "motus/compare/backends/motus_backend.hpp"

#include <string>

namespace motus::compare {

std::string MotusBackend::version() const { return version_.empty() ? "motus " MOTUS_VERSION ", double" : version_; }

void MotusBackend::build(const SceneDescription& scene, const Method& method, double dt) {
  if (!scene.mechanical) throw Unsupported(name_, {"first-order systems (compare runs point masses)"});
  sim_ = std::make_unique<Simulation>(scene, method, parts_);
  const MechanicalDescription& m = *scene.mechanical;
  sweeps_ = m.constraint_iterations;
  substeps_ = m.constraint_substeps;
  dt_ = dt;
  steps_ = 0;
  t0_ = scene.start_time;
}

// A plug-in's column in which none of its code runs — collision rules in a scene with no contacts
// to resolve, a projection with no sticks or contacts to project, and motus's own integrator —
// shows motus's own numbers under the plug-in's name: it says so.
std::vector<std::string> MotusBackend::notes() const {
  if (!sim_ || (!parts_.collisions && !parts_.constraints) || sim_->method().is_external()) return {};
  const World* world = sim_->world();
  if ((parts_.collisions && world->has_collisions()) || (parts_.constraints && world->has_constraints())) return {};
  const std::string mine = parts_.collisions && parts_.constraints ? "neither the plug-in's collision rules nor its projection runs"
                           : parts_.collisions                       ? "the plug-in's collision rules never run"
                                                                     : "the plug-in's projection never runs";
  return {mine + " in this scene (nothing here for " + (parts_.constraints && !parts_.collisions ? "it" : "them") +
          " to do with " + sim_->method().name() +
          "): this column is motus's own code"};
}

void MotusBackend::step() {
  // Whole steps of dt from the start, like the peers' world.Step(dt).
  ++steps_;
  sim_->advance(t0_ + static_cast<double>(steps_) * dt_, dt_, {});
}

void MotusBackend::read(Snapshot& out) const {
  const int n = sim_->mechanical_system()->size();
  const Vector& y = sim_->state();
  out.t = sim_->time();
  out.x.assign(y.data(), y.data() + n);
  out.v.assign(y.data() + n, y.data() + 2 * n);
}

std::vector<std::string> MotusBackend::settings() const {
  std::vector<std::string> s = {"integrator: " + sim_->method().name()};
  std::string passes;
  for (const auto& p : sim_->world()->passes()) passes += (passes.empty() ? "" : ", ") + p;
  s.push_back("passes: " + passes);
  if (parts_.collisions) s.push_back("collision response: the plug-in's (impulses and times of impact)");
  if (parts_.constraints) s.push_back("constraint projection: the plug-in's");
  if (sim_->world()->has_constraints()) {
    // (The peers step dt once, with their own iterations: motus's substeps are its solver's, as
    // their iterations are theirs, and the table's times include them.)
    // ("up to": the sweeps stop once only chains of sticks are left, solved exactly: docs/constraints.md.)
    const std::string sweeps = "up to " + std::to_string(sweeps_) + " projection " + (sweeps_ == 1 ? "sweep" : "sweeps");
    s.push_back(substeps_ == 1 ? "projection: " + sweeps + " per step"
                               : "projection: " + std::to_string(substeps_) + " substeps of dt/" +
                                     std::to_string(substeps_) + " per step, each with " + sweeps);
    if (sim_->world()->ignores_restitution())
      s.push_back("contacts are projected (Jakobsen): restitution is not applied (the peers apply it)");
  }
  return s;
}

}  // namespace motus::compare
