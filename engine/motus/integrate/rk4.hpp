#pragma once
// Classic fourth-order Runge–Kutta, as docs/course.md (section 4) writes it:
//   k1 = f(t_n, y_n)
//   k2 = f(t_n + h/2, y_n + (h/2) k1)
//   k3 = f(t_n + h/2, y_n + (h/2) k2)
//   k4 = f(t_n + h, y_n + h k3)
//   y_{n+1} = y_n + h (k1/6 + k2/3 + k3/3 + k4/6)
#include "motus/integrate/stage_vector.hpp"
#include "motus/systems/first_order_system.hpp"

namespace motus {

class Rk4 {
public:
  void resize(int n) {
    for (Vector* v : {&stages_.k1, &stages_.k2, &stages_.k3, &stages_.k4, &stages_.y_stage}) v->resize(n);
  }

  template <FirstOrder System>
  void step(System& f, double t, double h, VectorRef y) {
    if constexpr (constexpr int N = static_size_of<System>; N == Eigen::Dynamic) {
      step(f, t, h, y, stages_);
    } else {
      Stages<N> stages;
      step(f, t, h, y, stages);
    }
  }

private:
  template <int N>
  struct Stages {
    StageVector<N> k1, k2, k3, k4, y_stage;
  };

  template <class System, int N>
  static void step(System& f, double t, double h, VectorRef y, Stages<N>& s) {
    auto& [k1, k2, k3, k4, y_stage] = s;
    const Eigen::Index n = k1.size();
    f.derivative(t, y, k1);
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + 0.5 * h * k1[i];
    f.derivative(t + 0.5 * h, y_stage, k2);
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + 0.5 * h * k2[i];
    f.derivative(t + 0.5 * h, y_stage, k3);
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + h * k3[i];
    f.derivative(t + h, y_stage, k4);
    for (Eigen::Index i = 0; i < n; ++i) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  }

  Stages<Eigen::Dynamic> stages_;
};

}  // namespace motus
