#pragma once
// A mechanical system seen as a first-order one: y = [x; v], y' = [v; a(t, x, v)].
// This is how the Runge–Kutta family (euler, midpoint, rk4, rk45, ...) runs on
// point masses; the symplectic family uses the mechanical form directly.
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

}  // namespace motus
