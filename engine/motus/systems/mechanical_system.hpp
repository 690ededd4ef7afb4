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
  // The same for a system of one body in D dimensions, on arrays of D numbers: the same forces
  // in the same order, so the same numbers to the last bit, with every loop's bound known at
  // compile time (OneBodyAsFirstOrder, mechanical_as_first_order.hpp). Always inlined into the
  // integrator's step, so that its stages stay in registers.
  template <int D>
  [[gnu::always_inline]] void acceleration_of_one_body(double t, const double* x, const double* v, double* a) {
    ++evaluations;
    const Eigen::Map<const Vector> X(x, D), V(v, D);
    // Springs name their bodies by run-time indices; without them every index is known at
    // compile time and F stays in registers (a local of its own: the same sum, since springs
    // would only add to it).
    if (forces_.springs.empty()) {
      double F[D] = {};
      Eigen::Map<Vector> force(F, D);
      for (const auto& f : forces_.gravity) f.add_forces(D, one_mass_, X, force);
      for (const auto& f : forces_.drag) f.add_forces(D, V, force);
      for (const auto& f : forces_.central_gravity) f.add_forces(D, one_mass_, X, force);
      for (const auto& f : forces_.mutual_gravity) f.add_forces(D, one_mass_, X, force);
      for (const auto& f : forces_.pendulums) f.add_forces(D, one_mass_, X, force);
      for (int k = 0; k < D; ++k) a[k] = F[k] * inverse_mass_[0];
    } else {
      double F[D] = {};
      forces_.add_forces(t, D, one_mass_, X, V, Eigen::Map<Vector>(F, D));
      for (int k = 0; k < D; ++k) a[k] = F[k] * inverse_mass_[0];
    }
  }

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
  Eigen::Matrix<double, 1, 1> one_mass_;  // the first body's mass, for acceleration_of_one_body
  ForceSet forces_;
};

template <class S>
concept Mechanical = requires(S& s, double t, const Vector& x, Vector& a) {
  { s.size() } -> std::convertible_to<int>;
  s.acceleration(t, x, x, a);
};

}  // namespace motus
