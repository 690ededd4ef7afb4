#pragma once
// The mass on a spring, x'' = −(k/m)(x − anchor) − (c/m) x', solved exactly.
//   undamped (c = 0), ω = √(k/m):  x = x0 cos ωt + (v0/ω) sin ωt
//   underdamped, γ = c/2m, ω_d = √(ω² − γ²):
//     x = e^{−γt} (x0 cos ω_d t + ((v0 + γ x0)/ω_d) sin ω_d t)
// (x measured from the anchor; one coordinate at a time, since they do not mix.)
#include <cmath>

namespace motus {

struct HarmonicState {
  double x, v;
};

inline HarmonicState damped_harmonic(double x0, double v0, double omega, double gamma, double t) {
  const double wd = std::sqrt(omega * omega - gamma * gamma);
  const double A = x0, B = (v0 + gamma * x0) / wd;
  const double decay = std::exp(-gamma * t), c = std::cos(wd * t), s = std::sin(wd * t);
  const double x = decay * (A * c + B * s);
  const double v = decay * ((B * wd - gamma * A) * c - (A * wd + gamma * B) * s);
  return {x, v};
}

}  // namespace motus
