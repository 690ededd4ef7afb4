#pragma once
// Box2D 2.4.1 (float, 2-D) behind the backend interface, with the fair settings of
// docs/peers.md: world.Step(dt, 8, 3), restitution threshold 0, no sleep,
// no damping, no friction, fixed rotation, continuous collision for balls.
//
// The scene is built as it is in motus:
//   bodies   dynamic bodies with a circle of the body's radius and exactly its mass; a
//            point (radius 0) is a tiny circle that meets walls only (collision filter)
//   e        a contact's restitution is the product eA·eB (a PreSolve listener replaces
//            Box2D's max(eA, eB))
//   walls    static edges: a plane is a long edge, a box its four faces, a segment one
//            edge; planes and box faces are moved back by Box2D's edge skin
//            (b2_polygonRadius) so that their surface is where the scene puts it
//   forces   uniform gravity is the world's gravity; every other force is motus's
//            formula (PeerForces), applied with ApplyForceToCenter before every step
//   sticks   rigid b2DistanceJoints (length = min = max); pins make a body static there
// 1-D and 3-D scenes are refused: Box2D is 2-D.
#include <memory>

#include "motus/compare/backends/backend.hpp"

namespace motus::compare {

class Box2dBackend final : public Backend {
public:
  Box2dBackend();
  ~Box2dBackend() override;
  std::string name() const override { return "box2d"; }
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
