#include "motus/ball_lattice.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace motus {

double splitmix64_uniform(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;  // the top 53 bits: every double in [0, 1) on a 2^-53 grid
}

void shuffle_bodies(std::vector<BodyDescription>& bodies, std::uint64_t seed) {
  for (size_t i = bodies.size(); i-- > 1;)
    std::swap(bodies[i], bodies[static_cast<size_t>(splitmix64_uniform(seed) * static_cast<double>(i + 1))]);
}

void add_ball_lattice(MechanicalDescription& scene, const BallLattice& lattice) {
  const int d = scene.dimensions;
  // The smallest side with side^d ≥ count.
  long side = static_cast<long>(std::ceil(std::pow(static_cast<double>(lattice.count), 1.0 / d) - 1e-9));
  while (std::pow(static_cast<double>(side), d) < static_cast<double>(lattice.count)) ++side;
  std::uint64_t random = lattice.seed;
  // Room for all of them at once: growing a million bodies by doubling moves them ~20
  // times and touches twice the memory; and each body's two vectors get their size in
  // one allocation each rather than by push_back's doubling.
  scene.bodies.reserve(scene.bodies.size() + static_cast<size_t>(std::max(0L, lattice.count)));
  for (long n = 0; n < lattice.count; ++n) {
    BodyDescription& b = scene.bodies.emplace_back();
    b.mass = lattice.mass;
    b.radius = lattice.radius;
    b.restitution = lattice.restitution;
    b.position.resize(static_cast<size_t>(d));
    b.velocity.resize(static_cast<size_t>(d));
    long index = n;
    for (int k = 0; k < d; ++k) {
      b.position[static_cast<size_t>(k)] = lattice.origin[static_cast<size_t>(k)] +
                                           lattice.spacing * (static_cast<double>(index % side) + 0.5);
      index /= side;
    }
    for (int k = 0; k < d; ++k)
      b.velocity[static_cast<size_t>(k)] = lattice.speed * (2 * splitmix64_uniform(random) - 1);
  }
  if (lattice.container) {
    BoxCollider box;
    for (int k = 0; k < d; ++k) {
      box.min[k] = lattice.origin[k];
      box.max[k] = lattice.origin[k] + lattice.spacing * static_cast<double>(side);
    }
    box.restitution = 1;
    scene.colliders.boxes.push_back(box);
  }
}

}  // namespace motus
