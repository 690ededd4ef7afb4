#pragma once
// A body under uniform gravity g and linear drag F = −b v, solved exactly.
// With τ = m/b and the terminal velocity v_t = g τ:
//   v(t) = v_t + (v0 − v_t) e^{−t/τ}
//   x(t) = x0 + v_t t + (v0 − v_t) τ (1 − e^{−t/τ})
// (one coordinate at a time; −expm1 keeps 1 − e^{−t/τ} accurate for small t/τ).
#include <cmath>

namespace motus {

struct ProjectileState {
  double x, v;
};

inline ProjectileState projectile_with_drag(double x0, double v0, double g, double tau, double t) {
  const double vt = g * tau;
  const double one_minus_decay = -std::expm1(-t / tau);
  return {x0 + vt * t + (v0 - vt) * tau * one_minus_decay, vt + (v0 - vt) * (1 - one_minus_decay)};
}

}  // namespace motus
