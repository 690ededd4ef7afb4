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

  void add_forces(int d, const Vector& m, ConstVectorRef x, VectorRef F) const {
    F[body * d] -= m[body] * (g / length) * std::sin(x[body * d]);
  }
  double potential(int d, const Vector& m, ConstVectorRef x) const {
    return m[body] * (g / length) * (1 - std::cos(x[body * d]));
  }
};

}  // namespace motus
