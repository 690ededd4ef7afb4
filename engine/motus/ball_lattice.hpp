#pragma once
// The ball gas of the benchmarks and docs/peers.md: N balls on a square (cubic) lattice,
// velocities uniform in [−speed, speed]^d, inside a box container that fits the lattice.
// The random numbers come from SplitMix64 (Steele, Lea & Flood 2014) so that a seed
// gives the same balls on every machine and in every engine.
#include <array>
#include <cstdint>
#include <vector>

#include "motus/scene.hpp"

namespace motus {

struct BallLattice {
  long count = 100;
  double spacing = 2;      // m between neighbouring balls
  double radius = 0.5;     // m
  double mass = 1;         // kg
  double speed = 1;        // each velocity component uniform in [−speed, speed], m/s
  std::uint64_t seed = 1;
  double restitution = 1;  // the balls'; the container's walls have e = 1
  std::array<double, 3> origin{0, 0, 0};  // the container's lower corner
  bool container = true;
};

// Appends the balls (and, with `container`, a box around the lattice) to `scene`.
void add_ball_lattice(MechanicalDescription& scene, const BallLattice& lattice);

// Uniform in [0, 1) from a SplitMix64 state (which it advances).
double splitmix64_uniform(std::uint64_t& state);

// The bodies in a random order (Fisher–Yates with SplitMix64: the same order from the same seed
// on every machine), so that a body's number no longer tells where it is — as in a scene that
// lists its balls by hand. (Sticks and pins name bodies by number: for scenes without them.)
void shuffle_bodies(std::vector<BodyDescription>& bodies, std::uint64_t seed);

}  // namespace motus
