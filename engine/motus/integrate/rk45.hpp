#pragma once
// Dormand–Prince 5(4): seven stages give a fifth-order solution and an embedded
// fourth-order one; their difference is the error estimate that picks the next step
// (see step_size_control.hpp):
//   k_i     = f(t + c_i h, y_n + h Σ_{j<i} a_ij k_j),   i = 1 … 7
//   y_{n+1} = y_n + h Σ b_i k_i                (fifth order; b_2 = b_7 = 0)
//   e       = h Σ (b_i − b̂_i) k_i             (against the fourth-order ŷ_{n+1})
// k_7 is f at (t + h, y_{n+1}): the next step's k_1 ("first same as last"), so an
// accepted step costs six derivative evaluations.
#include <array>

#include "motus/integrate/stage_vector.hpp"
#include "motus/integrate/step_size_control.hpp"
#include "motus/systems/first_order_system.hpp"

namespace motus {

class Rk45 {
public:
  void resize(int n) {
    for (auto& k : stages_.k) k.resize(n);
    for (Vector* v : {&stages_.y_stage, &stages_.y_new, &stages_.error}) v->resize(n);
    have_first_stage_ = false;
  }
  void set_tolerance(Tolerance tol) { tol_ = tol; }

  template <FirstOrder System>
  bool try_step(System& f, double& t, double& h, VectorRef y) {
    if constexpr (constexpr int N = static_size_of<System>; N == Eigen::Dynamic) {
      return try_step(f, t, h, y, stages_);
    } else {
      Stages<N> stages;
      stages.k[0] = stages_.k[0];  // the cached first stage
      const bool accepted = try_step(f, t, h, y, stages);
      stages_.k[0] = stages.k[0];
      return accepted;
    }
  }

private:
  template <int N>
  struct Stages {
    std::array<StageVector<N>, 7> k;
    StageVector<N> y_stage, y_new, error;
  };

  template <class System, int N>
  bool try_step(System& f, double& t, double& h, VectorRef y, Stages<N>& s) {
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
    auto& [k1, k2, k3, k4, k5, k6, k7] = s.k;
    auto& y_stage = s.y_stage;
    const Eigen::Index n = y_stage.size();

    if (!have_first_stage_) {
      f.derivative(t, y, k1);
      have_first_stage_ = true;
    }
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + h * (a21 * k1[i]);
    f.derivative(t + c2 * h, y_stage, k2);
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + h * (a31 * k1[i] + a32 * k2[i]);
    f.derivative(t + c3 * h, y_stage, k3);
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
    f.derivative(t + c4 * h, y_stage, k4);
    for (Eigen::Index i = 0; i < n; ++i)
      y_stage[i] = y[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
    f.derivative(t + c5 * h, y_stage, k5);
    for (Eigen::Index i = 0; i < n; ++i)
      y_stage[i] = y[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    f.derivative(t + h, y_stage, k6);
    for (Eigen::Index i = 0; i < n; ++i)
      s.y_new[i] = y[i] + h * (b1 * k1[i] + b3 * k3[i] + b4 * k4[i] + b5 * k5[i] + b6 * k6[i]);
    f.derivative(t + h, s.y_new, k7);
    for (Eigen::Index i = 0; i < n; ++i)
      s.error[i] = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);

    const double err = scaled_error(y, s.y_new, s.error, tol_);
    const double h_used = h;
    h = control_.next_step(h, err);
    if (!(err <= 1)) return false;  // too large (or NaN: a state that is no longer finite), try again smaller
    y = s.y_new;
    t += h_used;
    k1.swap(k7);  // first same as last
    return true;
  }

  Stages<Eigen::Dynamic> stages_;
  bool have_first_stage_ = false;
  Tolerance tol_;
  StepSizeController control_{4};
};

}  // namespace motus
