#pragma once
// A mechanical system seen as a first-order one: y = [x; v], y' = [v; a(t, x, v)].
// This is how the Runge–Kutta family (euler, midpoint, rk4, rk45, dop853, ...) runs on
// point masses; the symplectic family uses the mechanical form directly.
//   MechanicalAsFirstOrder     any number of bodies, in d dimensions known at run time;
//   OneBodyAsFirstOrder<D>     one body in D dimensions: the state's 2D numbers are known at
//                              compile time (static_size), so an integrator keeps its stages in
//                              registers and the forces' loops unroll — the same numbers to the
//                              last bit (tests/test_dop853.cpp).
#include "motus/systems/mechanical_system.hpp"

namespace motus {

class MechanicalAsFirstOrder final {
public:
  explicit MechanicalAsFirstOrder(MechanicalSystem& system) : system_(system) {}

  int size() const { return 2 * system_.size(); }
  void derivative(double t, ConstVectorRef y, VectorRef dydt) {
    const int n = system_.size();
    dydt.head(n) = y.tail(n);
    system_.acceleration(t, y.head(n), y.tail(n), dydt.tail(n));
  }
  MechanicalSystem& mechanical() { return system_; }

private:
  MechanicalSystem& system_;
};

template <int D, unsigned Kinds = kAnyForces>  // Kinds: MechanicalSystem::acceleration_of_one_body
class OneBodyAsFirstOrder final {
public:
  static constexpr int static_size = 2 * D;
  explicit OneBodyAsFirstOrder(MechanicalSystem& system) : system_(system) {}

  int size() const { return static_size; }
  [[gnu::always_inline]] void derivative(double t, ConstVectorRef y, VectorRef dydt) {
    for (int k = 0; k < D; ++k) dydt[k] = y[D + k];
    system_.template acceleration_of_one_body<D, Kinds>(t, y.data(), y.data() + D, dydt.data() + D);
  }
  MechanicalSystem& mechanical() { return system_; }

private:
  MechanicalSystem& system_;
};

}  // namespace motus
