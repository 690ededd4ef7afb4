#pragma once
// The coursework engine behind the backend interface: motus::Simulation, stepped one dt
// at a time with the chosen integrator. Given outside parts (a student's plug-in), it is that
// plug-in's column: motus's world with the plug-in's collision response or projection.
#include <memory>

#include "motus/compare/backends/backend.hpp"
#include "motus/simulation.hpp"

namespace motus::compare {

class MotusBackend final : public Backend {
public:
  MotusBackend() = default;
  // A column of its own: `name` (the plug-in's), with its parts replacing motus's.
  MotusBackend(std::string name, std::string version, ExternalParts parts)
      : name_(std::move(name)), version_(std::move(version)), parts_(parts) {}
  std::string name() const override { return name_; }
  std::string version() const override;
  void build(const SceneDescription& scene, const Method& method, double dt) override;
  void step() override;
  void read(Snapshot& out) const override;
  std::vector<std::string> settings() const override;
  std::vector<std::string> notes() const override;

private:
  std::string name_ = "motus", version_;
  ExternalParts parts_;
  std::unique_ptr<Simulation> sim_;
  double dt_ = 0;
  long steps_ = 0;
  double t0_ = 0;
  int sweeps_ = 1, substeps_ = 1;      // the projection's, as the scene sets them
};

}  // namespace motus::compare
