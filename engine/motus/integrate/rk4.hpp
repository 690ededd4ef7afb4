#pragma once
// Classic fourth-order Runge–Kutta, as docs/course.md (section 4) writes it:
//   k1 = d(x_n) Δt
//   k2 = d(x_n + ½ k1) Δt
//   k3 = d(x_n + ½ k2) Δt
//   k4 = d(x_n + k3) Δt
//   x_{n+1} = x_n + k1/6 + k2/3 + k3/3 + k4/6
// Here k_i holds d(...) without the factor Δt, which is applied where k_i is used.
#include "motus/systems/first_order_system.hpp"

namespace motus {

class Rk4 {
public:
  void resize(int n) {
    k1_.resize(n);
    k2_.resize(n);
    k3_.resize(n);
    k4_.resize(n);
    y_stage_.resize(n);
  }

  template <FirstOrder System>
  void step(System& f, double t, double h, VectorRef y) {
    const Eigen::Index n = y.size();
    f.derivative(t, y, k1_);
    for (Eigen::Index i = 0; i < n; ++i) y_stage_[i] = y[i] + 0.5 * h * k1_[i];
    f.derivative(t + 0.5 * h, y_stage_, k2_);
    for (Eigen::Index i = 0; i < n; ++i) y_stage_[i] = y[i] + 0.5 * h * k2_[i];
    f.derivative(t + 0.5 * h, y_stage_, k3_);
    for (Eigen::Index i = 0; i < n; ++i) y_stage_[i] = y[i] + h * k3_[i];
    f.derivative(t + h, y_stage_, k4_);
    for (Eigen::Index i = 0; i < n; ++i) y[i] += h / 6 * (k1_[i] + 2 * k2_[i] + 2 * k3_[i] + k4_[i]);
  }

private:
  Vector k1_, k2_, k3_, k4_, y_stage_;
};

}  // namespace motus
