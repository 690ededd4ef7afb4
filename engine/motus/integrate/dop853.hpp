#pragma once
// Dormand–Prince 8(5,3), "DOP853" (Hairer, Nørsett & Wanner, Solving ODEs I, section II.10):
// twelve stages give an eighth-order solution
//   y_{n+1} = y_n + h (b1 k1 + b6 k6 + b7 k7 + … + b12 k12)
// and two embedded error estimates, one of fifth and one of third order:
//   e5 = h (er1 k1 + er6 k6 + … + er12 k12)
//   e3 = h (b1 k1 + … + b12 k12 − bhh1 k1 − bhh2 k9 − bhh3 k12)
// which are combined into one error of eighth order (see combined_error below),
//   err = ‖e5‖² / √(‖e5‖² + 0.01 ‖e3‖²)       (‖·‖ the scaled RMS norm of step_size_control.hpp)
// so the step is chosen with the exponent −1/8. The stage at y_{n+1} is the next step's first
// ("first same as last"), evaluated only once a step is accepted: an accepted step costs twelve
// derivative evaluations, a rejected one eleven.
// Tableau: Hairer's dop853.f (the same numbers as SciPy's DOP853, which uses the same error
// norm and step-size controller: safety 0.9, shrink ≥ 0.2, growth ≤ 10, no growth after a
// rejection).
#include <array>
#include <cmath>
#include <limits>

#include "motus/integrate/stage_vector.hpp"
#include "motus/integrate/step_size_control.hpp"
#include "motus/systems/first_order_system.hpp"

namespace motus {

class Dop853 {
public:
  void resize(int n) {
    for (auto& k : stages_.k) k.resize(n);
    for (Vector* v : {&stages_.y0, &stages_.y_stage, &stages_.y_new}) v->resize(n);
    have_first_stage_ = false;
  }
  void set_tolerance(Tolerance tol) { tol_ = tol; }

  // One attempt from (t, y) with step h. On success t and y advance; either way h becomes the
  // step to try next. Returns whether the step was accepted.
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

  // The combined error (Hairer's DOP853): with S5 = Σ (e5_i/sc_i)² and S3 = Σ (e3_i/sc_i)² over
  // the n variables (e without the factor h),
  //   err = |h| S5 / √(n (S5 + 0.01 S3))
  // — the fifth-order estimate, scaled down by the third-order one where that is larger.
  static double combined_error(double h, double sum5, double sum3, Eigen::Index n) {
    const double denominator = sum5 + 0.01 * sum3;
    if (denominator == 0) return 0;  // no error at all (a NaN goes on: the step is rejected)
    return std::abs(h) * sum5 / std::sqrt(denominator * static_cast<double>(n));
  }

private:
  template <int N>
  struct Stages {
    std::array<StageVector<N>, 12> k;
    StageVector<N> y0, y_stage, y_new;
  };

  template <class System, int N>
  bool try_step(System& f, double& t, double& h, VectorRef y, Stages<N>& s) {
    // The state as a stage of its own: nothing the derivative writes can alias it, nor t and h.
    StageVector<N>& y0 = s.y0;
    y0 = y;
    const double err = attempt(f, t, h, y0, s);
    const double h_used = h;
    h = control_.next_step(h, err);
    if (!(err <= 1)) return false;  // too large (or NaN: a state that is no longer finite), try again smaller
    y = s.y_new;
    t += h_used;
    f.derivative(t, s.y_new, s.k[0]);  // first same as last: the next step's k1
    return true;
  }

  // The stages of a step of h from (t, y0), y_new in s, and the step's error (accept when ≤ 1).
  template <class System, int N>
  double attempt(System& f, const double t, const double h, const StageVector<N>& y, Stages<N>& s) {
    // The nodes c_i and the rows a_ij of the tableau (a_i2 = a_i3 = 0 from row 4 on, etc.).
    constexpr double c2 = 0.526001519587677318785587544488e-1, c3 = 0.789002279381515978178381316732e-1,
                     c4 = 0.118350341907227396726757197510, c5 = 0.281649658092772603273242802490,
                     c6 = 0.333333333333333333333333333333, c7 = 0.25, c8 = 0.307692307692307692307692307692,
                     c9 = 0.651282051282051282051282051282, c10 = 0.6, c11 = 0.857142857142857142857142857142;
    constexpr double a21 = 5.26001519587677318785587544488e-2;
    constexpr double a31 = 1.97250569845378994544595329183e-2, a32 = 5.91751709536136983633785987549e-2;
    constexpr double a41 = 2.95875854768068491816892993775e-2, a43 = 8.87627564304205475450678981324e-2;
    constexpr double a51 = 2.41365134159266685502369798665e-1, a53 = -8.84549479328286085344864962717e-1,
                     a54 = 9.24834003261792003115737966543e-1;
    constexpr double a61 = 3.7037037037037037037037037037e-2, a64 = 1.70828608729473871279604482173e-1,
                     a65 = 1.25467687566822425016691814123e-1;
    constexpr double a71 = 3.7109375e-2, a74 = 1.70252211019544039314978060272e-1,
                     a75 = 6.02165389804559606850219397283e-2, a76 = -1.7578125e-2;
    constexpr double a81 = 3.70920001185047927108779319836e-2, a84 = 1.70383925712239993810214054705e-1,
                     a85 = 1.07262030446373284651809199168e-1, a86 = -1.53194377486244017527936158236e-2,
                     a87 = 8.27378916381402288758473766002e-3;
    constexpr double a91 = 6.24110958716075717114429577812e-1, a94 = -3.36089262944694129406857109825,
                     a95 = -8.68219346841726006818189891453e-1, a96 = 2.75920996994467083049415600797e1,
                     a97 = 2.01540675504778934086186788979e1, a98 = -4.34898841810699588477366255144e1;
    constexpr double a101 = 4.77662536438264365890433908527e-1, a104 = -2.48811461997166764192642586468,
                     a105 = -5.90290826836842996371446475743e-1, a106 = 2.12300514481811942347288949897e1,
                     a107 = 1.52792336328824235832596922938e1, a108 = -3.32882109689848629194453265587e1,
                     a109 = -2.03312017085086261358222928593e-2;
    constexpr double a111 = -9.3714243008598732571704021658e-1, a114 = 5.18637242884406370830023853209,
                     a115 = 1.09143734899672957818500254654, a116 = -8.14978701074692612513997267357,
                     a117 = -1.85200656599969598641566180701e1, a118 = 2.27394870993505042818970056734e1,
                     a119 = 2.49360555267965238987089396762, a1110 = -3.0467644718982195003823669022;
    constexpr double a121 = 2.27331014751653820792359768449, a124 = -1.05344954667372501984066689879e1,
                     a125 = -2.00087205822486249909675718444, a126 = -1.79589318631187989172765950534e1,
                     a127 = 2.79488845294199600508499808837e1, a128 = -2.85899827713502369474065508674,
                     a129 = -8.87285693353062954433549289258, a1210 = 1.23605671757943030647266201528e1,
                     a1211 = 6.43392746015763530355970484046e-1;
    // The eighth-order weights (b2 … b5 = 0).
    constexpr double b1 = 5.42937341165687622380535766363e-2, b6 = 4.45031289275240888144113950566,
                     b7 = 1.89151789931450038304281599044, b8 = -5.8012039600105847814672114227,
                     b9 = 3.1116436695781989440891606237e-1, b10 = -1.52160949662516078556178806805e-1,
                     b11 = 2.01365400804030348374776537501e-1, b12 = 4.47106157277725905176885569043e-2;
    // The third-order estimate's weights (subtracted from the b-sum) and the fifth-order one's.
    constexpr double bhh1 = 0.244094488188976377952755905512, bhh2 = 0.733846688281611857341361741547,
                     bhh3 = 0.220588235294117647058823529412e-1;
    constexpr double er1 = 0.1312004499419488073250102996e-1, er6 = -0.1225156446376204440720569753e+1,
                     er7 = -0.4957589496572501915214079952, er8 = 0.1664377182454986536961530415e+1,
                     er9 = -0.3503288487499736816886487290, er10 = 0.3341791187130174790297318841,
                     er11 = 0.8192320648511571246570742613e-1, er12 = -0.2235530786388629525884427845e-1;

    auto& [k1, k2, k3, k4, k5, k6, k7, k8, k9, k10, k11, k12] = s.k;
    auto& y_stage = s.y_stage;
    auto& y_new = s.y_new;
    const Eigen::Index n = y_stage.size();

    if (!have_first_stage_) {
      f.derivative(t, y, k1);
      have_first_stage_ = true;
    }
    // Stage j: y_j = y + h Σ a_jl k_l, written term by term as (h a_jl) k_l — the products h·a_jl
    // are the same for every i, and the newest stage comes last, a multiply and an add away from
    // the next evaluation.
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + h * a21 * k1[i];
    f.derivative(t + c2 * h, y_stage, k2);
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + h * a31 * k1[i] + h * a32 * k2[i];
    f.derivative(t + c3 * h, y_stage, k3);
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + h * a41 * k1[i] + h * a43 * k3[i];
    f.derivative(t + c4 * h, y_stage, k4);
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + h * a51 * k1[i] + h * a53 * k3[i] + h * a54 * k4[i];
    f.derivative(t + c5 * h, y_stage, k5);
    for (Eigen::Index i = 0; i < n; ++i) y_stage[i] = y[i] + h * a61 * k1[i] + h * a64 * k4[i] + h * a65 * k5[i];
    f.derivative(t + c6 * h, y_stage, k6);
    for (Eigen::Index i = 0; i < n; ++i)
      y_stage[i] = y[i] + h * a71 * k1[i] + h * a74 * k4[i] + h * a75 * k5[i] + h * a76 * k6[i];
    f.derivative(t + c7 * h, y_stage, k7);
    for (Eigen::Index i = 0; i < n; ++i)
      y_stage[i] = y[i] + h * a81 * k1[i] + h * a84 * k4[i] + h * a85 * k5[i] + h * a86 * k6[i] + h * a87 * k7[i];
    f.derivative(t + c8 * h, y_stage, k8);
    for (Eigen::Index i = 0; i < n; ++i)
      y_stage[i] = y[i] + h * a91 * k1[i] + h * a94 * k4[i] + h * a95 * k5[i] + h * a96 * k6[i] + h * a97 * k7[i] +
                   h * a98 * k8[i];
    f.derivative(t + c9 * h, y_stage, k9);
    for (Eigen::Index i = 0; i < n; ++i)
      y_stage[i] = y[i] + h * a101 * k1[i] + h * a104 * k4[i] + h * a105 * k5[i] + h * a106 * k6[i] +
                   h * a107 * k7[i] + h * a108 * k8[i] + h * a109 * k9[i];
    f.derivative(t + c10 * h, y_stage, k10);
    for (Eigen::Index i = 0; i < n; ++i)
      y_stage[i] = y[i] + h * a111 * k1[i] + h * a114 * k4[i] + h * a115 * k5[i] + h * a116 * k6[i] +
                   h * a117 * k7[i] + h * a118 * k8[i] + h * a119 * k9[i] + h * a1110 * k10[i];
    f.derivative(t + c11 * h, y_stage, k11);
    for (Eigen::Index i = 0; i < n; ++i)
      y_stage[i] = y[i] + h * a121 * k1[i] + h * a124 * k4[i] + h * a125 * k5[i] + h * a126 * k6[i] +
                   h * a127 * k7[i] + h * a128 * k8[i] + h * a129 * k9[i] + h * a1210 * k10[i] + h * a1211 * k11[i];
    f.derivative(t + h, y_stage, k12);

    // The new point, and the two error estimates in units of the tolerance.
    double sum5 = 0, sum3 = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      y_new[i] = y[i] + h * b1 * k1[i] + h * b6 * k6[i] + h * b7 * k7[i] + h * b8 * k8[i] + h * b9 * k9[i] +
                 h * b10 * k10[i] + h * b11 * k11[i] + h * b12 * k12[i];
      const double slope = b1 * k1[i] + b6 * k6[i] + b7 * k7[i] + b8 * k8[i] + b9 * k9[i] + b10 * k10[i] +
                           b11 * k11[i] + b12 * k12[i];
      const double scale = tol_.atol + tol_.rtol * std::max(std::abs(y[i]), std::abs(y_new[i]));
      const double e3 = (slope - bhh1 * k1[i] - bhh2 * k9[i] - bhh3 * k12[i]) / scale;
      const double e5 = (er1 * k1[i] + er6 * k6[i] + er7 * k7[i] + er8 * k8[i] + er9 * k9[i] + er10 * k10[i] +
                         er11 * k11[i] + er12 * k12[i]) /
                        scale;
      sum3 += e3 * e3;
      sum5 += e5 * e5;
    }
    // A finite step whose error, in units of a tolerance far below double precision (1e-200),
    // squares past the largest double: inf/inf made the error NaN, and the run blamed "an error
    // estimate that is not finite" instead of the tolerance. It is too large, which is what a
    // rejection and a smaller step say, down to the underflow that names the tolerance.
    if (!std::isfinite(sum5 + sum3) && y_new.allFinite()) return std::numeric_limits<double>::infinity();
    return combined_error(h, sum5, sum3, n);
  }

  Stages<Eigen::Dynamic> stages_;
  bool have_first_stage_ = false;
  Tolerance tol_;
  StepSizeController control_ = [] {
    StepSizeController c{7};  // err is of order 8: h_new = h · 0.9 · err^(−1/8)
    c.max_growth = 10;
    return c;
  }();
};

}  // namespace motus
