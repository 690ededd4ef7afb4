#pragma once
// The scene's forces that a peer engine does not model itself (springs, drag,
// inverse-square gravity, the pendulum law), computed with motus's own formulas from
// the peer's positions and velocities, so that the peer can apply them through its
// force API every step: the scenes really are the same. Uniform gravity is left to the
// peers' own world gravity (the same semi-implicit Euler kick).
#include <vector>

#include "motus/scene.hpp"

namespace motus::compare {

class PeerForces {
public:
  explicit PeerForces(const MechanicalDescription& scene);

  bool empty() const { return forces_.empty(); }
  // F (N·d numbers) at positions x and velocities v (N·d numbers each).
  void compute(double t, const std::vector<double>& x, const std::vector<double>& v, std::vector<double>& F) const;
  // Uniform gravity, summed (the peers' world gravity).
  const std::array<double, 3>& gravity() const { return gravity_; }

private:
  int d_;
  Vector mass_;
  ForceSet forces_;  // without uniform gravity
  std::array<double, 3> gravity_{0, 0, 0};
};

}  // namespace motus::compare
