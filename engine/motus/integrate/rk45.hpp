#pragma once
// Dormand–Prince 5(4): seven stages give a fifth-order solution and an embedded
// fourth-order one; their difference is the error estimate that picks the next step
// (see step_size_control.hpp). The last stage is the next step's first ("first same
// as last"), so an accepted step costs six derivative evaluations.
#include <array>

#include "motus/integrate/step_size_control.hpp"
#include "motus/systems/first_order_system.hpp"

namespace motus {

class Rk45 {
public:
  void resize(int n) {
    for (auto& k : k_) k.resize(n);
    y_stage_.resize(n);
    y_new_.resize(n);
    error_.resize(n);
    have_first_stage_ = false;
  }
  void set_tolerance(Tolerance tol) { tol_ = tol; }
  // Forget the cached first stage (call after changing y from outside).
  void reset() { have_first_stage_ = false; }

  template <FirstOrder System>
  bool try_step(System& f, double& t, double& h, VectorRef y) {
    // Butcher tableau of Dormand & Prince (1980).
    constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
    constexpr double a21 = 1.0 / 5;
    constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
    constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
    constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
    constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                     a65 = -5103.0 / 18656;
    constexpr double b1 = 35.0 / 384, b3 = 500.0 / 1113, b4 = 125.0 / 192, b5 = -2187.0 / 6784, b6 = 11.0 / 84;
    // b − b̂: the fifth-order weights minus the embedded fourth-order ones.
    constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                     e6 = 22.0 / 525, e7 = -1.0 / 40;
    auto& [k1, k2, k3, k4, k5, k6, k7] = k_;

    if (!have_first_stage_) {
      f.derivative(t, y, k1);
      have_first_stage_ = true;
    }
    y_stage_ = y + h * (a21 * k1);
    f.derivative(t + c2 * h, y_stage_, k2);
    y_stage_ = y + h * (a31 * k1 + a32 * k2);
    f.derivative(t + c3 * h, y_stage_, k3);
    y_stage_ = y + h * (a41 * k1 + a42 * k2 + a43 * k3);
    f.derivative(t + c4 * h, y_stage_, k4);
    y_stage_ = y + h * (a51 * k1 + a52 * k2 + a53 * k3 + a54 * k4);
    f.derivative(t + c5 * h, y_stage_, k5);
    y_stage_ = y + h * (a61 * k1 + a62 * k2 + a63 * k3 + a64 * k4 + a65 * k5);
    f.derivative(t + h, y_stage_, k6);
    y_new_ = y + h * (b1 * k1 + b3 * k3 + b4 * k4 + b5 * k5 + b6 * k6);
    f.derivative(t + h, y_new_, k7);
    error_ = h * (e1 * k1 + e3 * k3 + e4 * k4 + e5 * k5 + e6 * k6 + e7 * k7);

    const double err = scaled_error(y, y_new_, error_, tol_);
    const double h_used = h;
    h = control_.next_step(h, err);
    if (err > 1) return false;
    y = y_new_;
    t += h_used;
    k1.swap(k7);  // first same as last
    return true;
  }

private:
  std::array<Vector, 7> k_;
  Vector y_stage_, y_new_, error_;
  bool have_first_stage_ = false;
  Tolerance tol_;
  StepSizeController control_{4};
};

}  // namespace motus
