#pragma once
// Explicit Euler — the notes' update():   a = F/m;  v += a dt;  p += v dt
// For a first-order system y' = f(t, y):
//   y_{n+1} = y_n + Δt f(t_n, y_n)
// Global error O(Δt); on x'' = −ω²x the energy grows by (1 + ω²Δt²) every step.
#include "motus/systems/first_order_system.hpp"

namespace motus {

class Euler {
public:
  void resize(int n) { dydt_.resize(n); }

  template <FirstOrder System>
  void step(System& f, double t, double h, VectorRef y) {
    f.derivative(t, y, dydt_);
    y += h * dydt_;
  }

private:
  Vector dydt_;
};

}  // namespace motus
