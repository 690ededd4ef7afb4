#pragma once
// Bullet 3.24 (the double build, -DBT_USE_DOUBLE_PRECISION) behind the backend interface:
// one btRigidBody with a btSphereShape per body, btStaticPlaneShape walls, the scene's
// uniform gravity as the world's gravity and every other force applied with
// applyCentralForce each step (motus's formulas, PeerForces), sticks as one-row rigid
// distance constraints solved by Bullet's own sequential-impulse solver, pins as static
// bodies. 2-D scenes live in the z = 0 plane, 1-D scenes on the x axis (linear factors).
// Bullet's headers stay in the .cpp: only the motus_compare target is compiled with
// BT_USE_DOUBLE_PRECISION (through pkg-config's bullet-float64), and a btScalar of the wrong width would break the ABI.
#include <memory>

#include "motus/compare/backends/backend.hpp"

namespace motus::compare {

class BulletBackend final : public Backend {
public:
  BulletBackend();
  ~BulletBackend() override;
  std::string name() const override { return "bullet"; }
  std::string version() const override;
  void build(const SceneDescription& scene, const Method& method, double dt) override;
  void step() override;
  void read(Snapshot& out) const override;
  std::vector<std::string> settings() const override;
  std::vector<std::string> notes() const override;
  void watch_for_notes(bool on) override { watching_ = on; }

private:
  struct World;  // the engine's objects, kept out of this header
  std::unique_ptr<World> world_;
  bool watching_ = true;
};

}  // namespace motus::compare
