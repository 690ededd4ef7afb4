#pragma once
// STUB: being written (issue 4).
#include <memory>

#include "backend.hpp"

namespace motus::compare {

class Box2dBackend final : public Backend {
public:
  Box2dBackend();
  ~Box2dBackend() override;
  std::string name() const override { return "box2d"; }
  std::string version() const override;
  void build(const SceneDescription& scene, Integrator integrator, double dt) override;
  void step() override;
  void read(Snapshot& out) const override;
  std::vector<std::string> settings() const override;
  std::vector<std::string> notes() const override;

private:
  struct World;  // the engine's objects, kept out of this header
  std::unique_ptr<World> world_;
};

}  // namespace motus::compare
