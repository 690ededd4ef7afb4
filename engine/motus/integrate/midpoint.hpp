#pragma once
// The midpoint method (second-order Runge–Kutta), as docs/course.md (section 4) writes it:
//   k1 = f(t_n, y_n)
//   k2 = f(t_n + h/2, y_n + (h/2) k1)
//   y_{n+1} = y_n + h k2
#include "motus/integrate/stage_vector.hpp"
#include "motus/systems/first_order_system.hpp"

namespace motus {

class Midpoint {
public:
  void resize(int n) {
    stages_.k1.resize(n);
    stages_.k2.resize(n);
    stages_.y_mid.resize(n);
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
    StageVector<N> k1, k2, y_mid;
  };

  template <class System, int N>
  static void step(System& f, double t, double h, VectorRef y, Stages<N>& s) {
    auto& [k1, k2, y_mid] = s;
    const Eigen::Index n = k1.size();
    f.derivative(t, y, k1);
    for (Eigen::Index i = 0; i < n; ++i) y_mid[i] = y[i] + 0.5 * h * k1[i];
    f.derivative(t + 0.5 * h, y_mid, k2);
    for (Eigen::Index i = 0; i < n; ++i) y[i] += h * k2[i];
  }

  Stages<Eigen::Dynamic> stages_;
};

}  // namespace motus
