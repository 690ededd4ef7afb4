#pragma once
// Error control for the adaptive integrators (Hairer–Nørsett–Wanner, the controller
// of DOPRI5):
//   err = √( mean_i ((y1_i − ŷ1_i) / sc_i)² ),  sc_i = atol + rtol · max(|y0_i|, |y1_i|)
//   accept when err ≤ 1;  h_new = h · min(fac_max, max(fac_min, 0.9 · err^(−1/(q+1))))
// with q the lower order of the pair and no growth right after a rejection.
#include <algorithm>
#include <cmath>

#include "motus/vector.hpp"

namespace motus {

struct Tolerance {
  double atol = 1e-9;
  double rtol = 1e-6;
};

// The scaled RMS norm of a step's error estimate e (err above): for an embedded pair (rk45, dop853)
// e = y1 − ŷ1, for rk4-doubling e = (y_half − y_full)/15. y0 (the step's start) and y1 (its end)
// only set each component's scale sc_i.
inline double scaled_error(ConstVectorRef y0, ConstVectorRef y1, ConstVectorRef error, Tolerance tol) {
  double sum = 0;
  for (Eigen::Index i = 0; i < y0.size(); ++i) {
    const double scale = tol.atol + tol.rtol * std::max(std::abs(y0[i]), std::abs(y1[i]));
    const double e = error[i] / scale;
    sum += e * e;
  }
  return std::sqrt(sum / static_cast<double>(y0.size()));
}

class StepSizeController {
public:
  explicit StepSizeController(int lower_order) : exponent_(-1.0 / (lower_order + 1)) {}

  // The step to try next after a step of size h had scaled error err.
  double next_step(double h, double err) {
    const bool accepted = err <= 1;
    double factor = err == 0 ? max_growth : safety * power_of(err);
    factor = std::clamp(factor, max_shrink, max_growth);
    if (accepted && rejected_last_) factor = std::min(factor, 1.0);
    rejected_last_ = !accepted;
    return h * factor;
  }

  double safety = 0.9;
  double max_shrink = 0.2;  // fac_min
  double max_growth = 5.0;  // fac_max

private:
  // err^exponent; err^(−1/8) (dop853) as three square roots, the same to rounding and cheaper
  // than pow, which otherwise costs a tenth of a dop853 step on a small system.
  double power_of(double err) const {
    if (exponent_ == -1.0 / 8) return 1 / std::sqrt(std::sqrt(std::sqrt(err)));
    return std::pow(err, exponent_);
  }

  double exponent_;
  bool rejected_last_ = false;
};

}  // namespace motus
