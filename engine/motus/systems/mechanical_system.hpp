#pragma once
// A mechanical system: point masses with positions x, velocities v, masses m and
// forces F(t, x, v), in 1, 2 or 3 dimensions. a = F/m is all the symplectic
// integrators ask of it; energies and momenta are what the tests and reports ask.
#include <string>
#include <vector>

#include "motus/forces/force_set.hpp"
#include "motus/vector.hpp"

namespace motus {

class MechanicalSystem {
public:
  MechanicalSystem(int dimensions, std::vector<double> masses, ForceSet forces);

  int dimensions() const { return d_; }
  int particles() const { return static_cast<int>(mass_.size()); }
  // Number of coordinates: particles × dimensions.
  int size() const { return particles() * d_; }
  const Vector& masses() const { return mass_; }
  const ForceSet& forces() const { return forces_; }

  // a = F(t, x, v) / m. Allocates nothing.
  void acceleration(double t, ConstVectorRef x, ConstVectorRef v, VectorRef a);

  double kinetic_energy(ConstVectorRef v) const;
  double potential_energy(ConstVectorRef x) const;
  Vector momentum(ConstVectorRef v) const;
  // About the origin: one component in 2D (the z axis), three in 3D, none in 1D.
  Vector angular_momentum(ConstVectorRef x, ConstVectorRef v) const;

  long evaluations = 0;  // acceleration calls so far

private:
  int d_;
  Vector mass_;
  Vector inverse_mass_;
  Vector coordinate_inverse_mass_;  // 1/m_i for each of body i's coordinates
  ForceSet forces_;
};

template <class S>
concept Mechanical = requires(S& s, double t, const Vector& x, Vector& a) {
  { s.size() } -> std::convertible_to<int>;
  s.acceleration(t, x, x, a);
};

}  // namespace motus
