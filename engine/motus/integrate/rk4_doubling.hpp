#pragma once
// Adaptive RK4 by step doubling (docs/course.md, section 5):
//   take one RK4 step of h, and two of h/2, from the same point;
//   e = (y_half − y_full)/15 estimates the error of the two half steps;
//   keep the step if that error is within tolerance, and then use the extrapolated
//   y = y_half + e, which is fifth order;
//   h ← h · 0.9 · err^(−1/5), within [h/5, 5h], with no growth right after a rejection
//   (step_size_control.hpp).
#include "motus/integrate/rk4.hpp"
#include "motus/integrate/stage_vector.hpp"
#include "motus/integrate/step_size_control.hpp"

namespace motus {

class Rk4Doubling {
public:
  void resize(int n) {
    rk4_.resize(n);
    for (Vector* v : {&stages_.y_full, &stages_.y_half, &stages_.error}) v->resize(n);
  }
  void set_tolerance(Tolerance tol) { tol_ = tol; }

  // One attempt from (t, y) with step h. On success t and y advance; either way h
  // becomes the step to try next. Returns whether the step was accepted.
  template <FirstOrder System>
  bool try_step(System& f, double& t, double& h, VectorRef y) {
    if constexpr (constexpr int N = static_size_of<System>; N == Eigen::Dynamic) {
      return try_step(f, t, h, y, stages_);
    } else {
      Stages<N> stages;
      return try_step(f, t, h, y, stages);
    }
  }

private:
  template <int N>
  struct Stages {
    StageVector<N> y_full, y_half, error;  // error: e = (y_half − y_full)/15
  };

  template <class System, int N>
  bool try_step(System& f, double& t, double& h, VectorRef y, Stages<N>& s) {
    auto& [y_full, y_half, error] = s;
    const Eigen::Index n = y_full.size();
    y_full = y;
    rk4_.step(f, t, h, y_full);
    y_half = y;
    rk4_.step(f, t, 0.5 * h, y_half);
    rk4_.step(f, t + 0.5 * h, 0.5 * h, y_half);
    for (Eigen::Index i = 0; i < n; ++i) error[i] = (y_half[i] - y_full[i]) / 15;
    const double err = scaled_error(y, y_half, error, tol_);
    const double h_used = h;
    h = control_.next_step(h, err);
    if (!(err <= 1)) return false;  // too large (or NaN: a state that is no longer finite), try again smaller
    for (Eigen::Index i = 0; i < n; ++i) y[i] = y_half[i] + error[i];  // y_half + e: fifth order
    t += h_used;
    return true;
  }

  Rk4 rk4_;
  Stages<Eigen::Dynamic> stages_;
  Tolerance tol_;
  StepSizeController control_{4};
};

}  // namespace motus
