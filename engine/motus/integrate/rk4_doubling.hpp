#pragma once
// Adaptive RK4 by step doubling — the course's "change Δt as you go along, depending
// on how much things are changing" (docs/course.md, section 5):
//   take one RK4 step of h, and two of h/2, from the same point;
//   their difference / 15 estimates the error of the two half steps;
//   keep the step if that error is within tolerance, and then use the extrapolated
//   y = y_half + (y_half − y_full)/15, which is fifth order;
//   grow or shrink h by (1/err)^(1/5).
#include "motus/integrate/rk4.hpp"
#include "motus/integrate/step_size_control.hpp"

namespace motus {

class Rk4Doubling {
public:
  void resize(int n) {
    rk4_.resize(n);
    y_full_.resize(n);
    y_half_.resize(n);
    difference_.resize(n);
  }
  void set_tolerance(Tolerance tol) { tol_ = tol; }

  // One attempt from (t, y) with step h. On success t and y advance; either way h
  // becomes the step to try next. Returns whether the step was accepted.
  template <FirstOrder System>
  bool try_step(System& f, double& t, double& h, VectorRef y) {
    y_full_ = y;
    rk4_.step(f, t, h, y_full_);
    y_half_ = y;
    rk4_.step(f, t, 0.5 * h, y_half_);
    rk4_.step(f, t + 0.5 * h, 0.5 * h, y_half_);
    difference_ = (y_half_ - y_full_) / 15;
    const double err = scaled_error(y, y_half_, difference_, tol_);
    const double h_used = h;
    h = control_.next_step(h, err);
    if (err > 1) return false;
    y = y_half_ + difference_;
    t += h_used;
    return true;
  }

private:
  Rk4 rk4_;
  Vector y_full_, y_half_, difference_;
  Tolerance tol_;
  StepSizeController control_{4};
};

}  // namespace motus
