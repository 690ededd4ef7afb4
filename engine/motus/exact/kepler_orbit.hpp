#pragma once
// Kepler's problem r'' = −μ r/|r|³ solved exactly for an elliptic orbit, by
// Lagrange's f and g functions and Kepler's equation in the eccentric anomaly:
//   a = 1/(2/r0 − v0²/μ),  n = √(μ/a³),  σ0 = r0·v0/√μ
//   n t = ΔE − (1 − r0/a) sin ΔE + (σ0/√a)(1 − cos ΔE)      (solved for ΔE by Newton)
//   r = a + (r0 − a) cos ΔE + σ0 √a sin ΔE
//   f = 1 − (a/r0)(1 − cos ΔE),  g = t − √(a³/μ)(ΔE − sin ΔE)
//   ḟ = −√(μa) sin ΔE/(r r0),    ġ = 1 − (a/r)(1 − cos ΔE)
//   x = f x0 + g v0,  v = ḟ x0 + ġ v0
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace motus {

struct KeplerState {
  std::array<double, 2> x, v;
};

inline KeplerState kepler_orbit(std::array<double, 2> x0, std::array<double, 2> v0, double mu, double t) {
  const double r0 = std::hypot(x0[0], x0[1]);
  const double v2 = v0[0] * v0[0] + v0[1] * v0[1];
  const double a = 1 / (2 / r0 - v2 / mu);
  if (!(a > 0)) throw std::invalid_argument("the exact Kepler solution is for elliptic orbits only");
  const double n = std::sqrt(mu / (a * a * a));
  const double period = 2 * std::numbers::pi / n;
  const double tau = t - period * std::floor(t / period);  // whole orbits change nothing
  const double sigma0 = (x0[0] * v0[0] + x0[1] * v0[1]) / std::sqrt(mu);
  const double sa = std::sqrt(a);

  // Newton on F(E) = E − (1 − r0/a) sin E + (σ0/√a)(1 − cos E) − n τ, F' = r/a > 0.
  double E = n * tau;
  for (int i = 0; i < 100; ++i) {
    const double F = E - (1 - r0 / a) * std::sin(E) + sigma0 / sa * (1 - std::cos(E)) - n * tau;
    const double dF = 1 - (1 - r0 / a) * std::cos(E) + sigma0 / sa * std::sin(E);
    const double step = F / dF;
    E -= step;
    if (std::abs(step) < 1e-16 * (1 + std::abs(E))) break;
  }
  const double c = std::cos(E), s = std::sin(E);
  const double r = a + (r0 - a) * c + sigma0 * sa * s;
  const double f = 1 - a / r0 * (1 - c);
  const double g = tau - std::sqrt(a * a * a / mu) * (E - s);
  const double fdot = -std::sqrt(mu * a) * s / (r * r0);
  const double gdot = 1 - a / r * (1 - c);
  KeplerState out{};
  for (int k = 0; k < 2; ++k) {
    out.x[k] = f * x0[k] + g * v0[k];
    out.v[k] = fdot * x0[k] + gdot * v0[k];
  }
  return out;
}

}  // namespace motus
