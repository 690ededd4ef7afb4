#pragma once
// The midpoint method (second-order Runge–Kutta), as on the notes' slide:
//   k1 = d(x_n) Δt
//   k2 = d(x_n + ½ k1) Δt
//   x_{n+1} = x_n + k2
#include "motus/systems/first_order_system.hpp"

namespace motus {

class Midpoint {
public:
  void resize(int n) {
    k1_.resize(n);
    k2_.resize(n);
    y_mid_.resize(n);
  }

  template <FirstOrder System>
  void step(System& f, double t, double h, VectorRef y) {
    f.derivative(t, y, k1_);
    k1_ *= h;
    y_mid_ = y + 0.5 * k1_;
    f.derivative(t + 0.5 * h, y_mid_, k2_);
    y += h * k2_;
  }

private:
  Vector k1_, k2_, y_mid_;
};

}  // namespace motus
