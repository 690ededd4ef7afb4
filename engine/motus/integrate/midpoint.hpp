#pragma once
// The midpoint method (second-order Runge–Kutta), as docs/course.md (section 4) writes it:
//   k1 = d(x_n) Δt
//   k2 = d(x_n + ½ k1) Δt
//   x_{n+1} = x_n + k2
// Here k_i holds d(...) without the factor Δt, which is applied where k_i is used.
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
    const Eigen::Index n = y.size();
    f.derivative(t, y, k1_);
    for (Eigen::Index i = 0; i < n; ++i) y_mid_[i] = y[i] + 0.5 * h * k1_[i];
    f.derivative(t + 0.5 * h, y_mid_, k2_);
    for (Eigen::Index i = 0; i < n; ++i) y[i] += h * k2_[i];
  }

private:
  Vector k1_, k2_, y_mid_;
};

}  // namespace motus
