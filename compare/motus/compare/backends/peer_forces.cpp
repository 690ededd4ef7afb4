#include "motus/compare/backends/peer_forces.hpp"

namespace motus::compare {

PeerForces::PeerForces(const MechanicalDescription& scene) : d_(scene.dimensions), forces_(scene.forces) {
  mass_.resize(static_cast<Eigen::Index>(scene.bodies.size()));
  for (size_t i = 0; i < scene.bodies.size(); ++i) mass_[static_cast<Eigen::Index>(i)] = scene.bodies[i].mass;
  for (const auto& g : forces_.gravity)
    for (int k = 0; k < 3; ++k) gravity_[k] += g.g[k];
  forces_.gravity.clear();
}

void PeerForces::compute(double t, const std::vector<double>& x, const std::vector<double>& v,
                         std::vector<double>& F) const {
  F.assign(x.size(), 0.0);
  if (forces_.empty()) return;
  const Eigen::Map<const Vector> X(x.data(), static_cast<Eigen::Index>(x.size()));
  const Eigen::Map<const Vector> V(v.data(), static_cast<Eigen::Index>(v.size()));
  Eigen::Map<Vector> out(F.data(), static_cast<Eigen::Index>(F.size()));
  forces_.add_forces(t, d_, mass_, X, V, out);
}

}  // namespace motus::compare
