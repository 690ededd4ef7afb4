#pragma once
// Explicit Euler (docs/course.md, sections 2 and 4). For a first-order system y' = f(t, y):
//   y_{n+1} = y_n + Δt f(t_n, y_n)
// For a body, y = [x; v]: x += v Δt and v += a Δt, both with the values at the start of
// the step — the course's spring table. (Updating v first and moving x with the new v
// is symplectic Euler, symplectic_euler.hpp.)
// Global error O(Δt); on x'' = −ω²x the energy grows by (1 + ω²Δt²) every step.
// (Why the Runge–Kutta family's steps are plain loops over i: stage_vector.hpp.)
#include "motus/integrate/stage_vector.hpp"
#include "motus/systems/first_order_system.hpp"

namespace motus {

class Euler {
public:
  void resize(int n) { dydt_.resize(n); }

  template <FirstOrder System>
  void step(System& f, double t, double h, VectorRef y) {
    if constexpr (constexpr int N = static_size_of<System>; N == Eigen::Dynamic) {
      step(f, t, h, y, dydt_);
    } else {
      StageVector<N> dydt;
      step(f, t, h, y, dydt);
    }
  }

private:
  template <class System, class Stage>
  static void step(System& f, double t, double h, VectorRef y, Stage& dydt) {
    f.derivative(t, y, dydt);
    for (Eigen::Index i = 0; i < dydt.size(); ++i) y[i] += h * dydt[i];
  }

  Vector dydt_;
};

}  // namespace motus
