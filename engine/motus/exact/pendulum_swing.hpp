#pragma once
// The simple pendulum θ'' = −ω0² sin θ (ω0 = √(g/L)) started at the bottom with
// θ(0) = 0, θ'(0) = 2kω0 (k < 1: it swings, not loops), solved exactly:
//   θ(t) = 2 arcsin(k sn(ω0 t, k)),   θ'(t) = 2 k ω0 cn(ω0 t, k)
// with Jacobi's elliptic functions sn and cn of modulus k, computed by the
// arithmetic–geometric mean (Abramowitz & Stegun 16.4).
#include <cmath>
#include <stdexcept>

namespace motus {

struct SnCn {
  double sn, cn;
};

inline SnCn jacobi_sn_cn(double u, double k) {
  // Descending Landen transformation: a_{n+1} = (a_n + b_n)/2, b_{n+1} = √(a_n b_n),
  // c_{n+1} = (a_n − b_n)/2, until c vanishes; then φ_N = 2^N a_N u and
  // φ_{n−1} = (φ_n + arcsin((c_n/a_n) sin φ_n))/2; sn = sin φ_0, cn = cos φ_0.
  double a[16], c[16];
  double b = std::sqrt(1 - k * k);
  a[0] = 1;
  c[0] = k;
  int n = 0;
  while (std::abs(c[n]) > 1e-16 && n < 15) {
    a[n + 1] = 0.5 * (a[n] + b);
    c[n + 1] = 0.5 * (a[n] - b);
    b = std::sqrt(a[n] * b);
    ++n;
  }
  double phi = std::ldexp(a[n] * u, n);
  for (int i = n; i > 0; --i) phi = 0.5 * (phi + std::asin(c[i] / a[i] * std::sin(phi)));
  return {std::sin(phi), std::cos(phi)};
}

struct PendulumState {
  double theta, omega;
};

inline PendulumState pendulum_swing(double theta_dot_0, double g_over_L, double t) {
  const double w0 = std::sqrt(g_over_L);
  const double k = theta_dot_0 / (2 * w0);  // θ'(0) = 2kω0
  if (!(std::abs(k) < 1)) throw std::invalid_argument("the exact pendulum solution is for swings (|θ'(0)| < 2√(g/L))");
  const SnCn e = jacobi_sn_cn(w0 * t, std::abs(k));
  const double sign = k < 0 ? -1 : 1;
  return {sign * 2 * std::asin(std::abs(k) * e.sn), 2 * k * w0 * e.cn};
}

}  // namespace motus
