#pragma once
// A mechanical system: point masses with positions x, velocities v, masses m and
// forces F(t, x, v), in 1, 2 or 3 dimensions. a = F/m is all the symplectic
// integrators ask of it; energies and momenta are what the tests and reports ask.
#include <string>
#include <vector>

#include "motus/forces/force_set.hpp"
#include "motus/vector.hpp"

namespace motus {

// Which kinds of force a one-body path takes into account, as bits, so that a run whose forces are
// known (Kepler: central gravity only) is compiled without the loops over the empty kinds: even
// empty, they cost a quarter of an evaluation. kAnyForces: every kind, springs included.
enum ForceKinds : unsigned {
  kGravityForce = 1,
  kDragForce = 2,
  kCentralGravityForce = 4,
  kMutualGravityForce = 8,
  kPendulumForce = 16,
  kAnyForces = ~0u,
};

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
  //   Kinds: the force kinds the scene has (one_body_force_kinds()), or kAnyForces for whatever it has.
  template <int D, unsigned Kinds = kAnyForces>
  [[gnu::always_inline]] void acceleration_of_one_body(double t, const double* x, const double* v, double* a) {
    ++evaluations;
    // Springs name their bodies by run-time indices; without them every index is known at
    // compile time, and x, v and F are fixed-size locals the compiler keeps in registers (copies:
    // the same numbers; F a sum of its own, since springs would only add to it). Through Refs
    // instead, F lives in memory and every force's sum waits on a store (1.5× Odeint's cost per
    // evaluation on Kepler, bench/bench_precision).
    if (Kinds != kAnyForces || forces_.springs.empty()) {
      using Fixed = Eigen::Matrix<double, D, 1>;
      const Fixed X = Eigen::Map<const Fixed>(x), V = Eigen::Map<const Fixed>(v);
      Fixed F = Fixed::Zero();
      if constexpr ((Kinds & kGravityForce) != 0)
        for (const auto& f : forces_.gravity) f.add_forces(D, one_mass_, X, F);
      if constexpr ((Kinds & kDragForce) != 0)
        for (const auto& f : forces_.drag) f.add_forces(D, V, F);
      if constexpr ((Kinds & kCentralGravityForce) != 0)
        for (const auto& f : forces_.central_gravity) f.add_forces(D, one_mass_, X, F);
      if constexpr ((Kinds & kMutualGravityForce) != 0)
        for (const auto& f : forces_.mutual_gravity) f.add_forces(D, one_mass_, X, F);
      if constexpr ((Kinds & kPendulumForce) != 0)
        for (const auto& f : forces_.pendulums) f.add_forces(D, one_mass_, X, F);
      // One vector store, not D scalar ones: the integrator's next stage reads a back as a vector,
      // and a wide load of narrow stores stalls (store forwarding fails: ~1.4× the cost per
      // evaluation on Kepler). The same products.
      Eigen::Map<Fixed> acceleration(a);
      acceleration = F * inverse_mass_[0];
    } else {
      const Eigen::Map<const Vector> X(x, D), V(v, D);
      double F[D] = {};
      forces_.add_forces(t, D, one_mass_, X, V, Eigen::Map<Vector>(F, D));
      for (int k = 0; k < D; ++k) a[k] = F[k] * inverse_mass_[0];
    }
  }

  // The kinds of force present, as ForceKinds bits; kAnyForces when there are springs (they take
  // the general path).
  unsigned one_body_force_kinds() const {
    if (!forces_.springs.empty()) return kAnyForces;
    return (forces_.gravity.empty() ? 0u : kGravityForce) | (forces_.drag.empty() ? 0u : kDragForce) |
           (forces_.central_gravity.empty() ? 0u : kCentralGravityForce) |
           (forces_.mutual_gravity.empty() ? 0u : kMutualGravityForce) | (forces_.pendulums.empty() ? 0u : kPendulumForce);
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
  Vector coordinate_inverse_mass_;  // 1/m_i for each of body i's coordinates
  Eigen::Matrix<double, 1, 1> one_mass_;  // the first body's mass, for acceleration_of_one_body
  ForceSet forces_;
};

template <class S>
concept Mechanical = requires(S& s, double t, const Vector& x, Vector& a) {
  { s.size() } -> std::convertible_to<int>;
  s.acceleration(t, x, x, a);
};

}  // namespace motus
