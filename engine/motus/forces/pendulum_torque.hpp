#pragma once
// The simple pendulum θ'' = −(g/L) sin θ, written as a 1-D body whose coordinate is
// the angle θ (radians) and whose velocity is θ' (rad/s):
//   "force"  F = −m (g/L) sin θ,   potential U = m (g/L) (1 − cos θ).
// Energies of such a body are the pendulum's true energies divided by L².
#include <cmath>

#include "motus/vector.hpp"

namespace motus {

struct PendulumTorque {
  int body = 0;
  double g = 9.81;     // m/s²
  double length = 1;   // m

  template <class Masses, class X, class Forces>  // Vectors (or Refs), or fixed-size ones for one body
  void add_forces(int d, const Masses& m, const X& x, Forces&& F) const {
    for (Eigen::Index i = 0; i < m.size(); ++i)  // only `body`; a loop of known bound for one body
      if (i == body) F[i * d] -= m[i] * (g / length) * std::sin(x[i * d]);
  }
  double potential(int d, const Vector& m, ConstVectorRef x) const {
    return m[body] * (g / length) * (1 - std::cos(x[body * d]));
  }
};

}  // namespace motus
