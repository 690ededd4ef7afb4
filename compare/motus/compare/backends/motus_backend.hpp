#pragma once
// The coursework engine behind the backend interface: motus::Simulation, stepped one dt
// at a time with the chosen integrator.
#include <memory>

#include "motus/compare/backends/backend.hpp"
#include "motus/simulation.hpp"

namespace motus::compare {

class MotusBackend final : public Backend {
public:
  std::string name() const override { return "motus"; }
  std::string version() const override;
  void build(const SceneDescription& scene, Integrator integrator, double dt) override;
  void step() override;
  void read(Snapshot& out) const override;
  std::vector<std::string> settings() const override;

  const Simulation& simulation() const { return *sim_; }

private:
  std::unique_ptr<Simulation> sim_;
  double dt_ = 0;
  long steps_ = 0;
  double t0_ = 0;
};

}  // namespace motus::compare
