#pragma once
// A Hooke spring between body a and body b, or between body a and a fixed anchor.
//   d = x_a − x_b,  F_a = −k (|d| − L) d̂ − c ((v_a − v_b)·d̂) d̂,  F_b = −F_a
// A zero-length spring (L = 0) is F_a = −k d − c (v_a − v_b): the same law without
// the direction, which also makes sense when d = 0 (the course's f = −kx).
// Potential U = ½ k (|d| − L)².
#include <array>
#include <cmath>

#include "motus/vector.hpp"

namespace motus {

struct Spring {
  int a = 0;
  int b = -1;                          // −1: the spring is tied to `anchor`
  std::array<double, 3> anchor{0, 0, 0};
  double stiffness = 0;                // k, N/m
  double rest_length = 0;              // L, m
  double damping = 0;                  // c, N·s/m

  void add_forces(int d, ConstVectorRef x, ConstVectorRef v, VectorRef F) const {
    double dx[3] = {0, 0, 0}, dv[3] = {0, 0, 0};
    for (int k = 0; k < d; ++k) {
      dx[k] = x[a * d + k] - (b >= 0 ? x[b * d + k] : anchor[k]);
      dv[k] = v[a * d + k] - (b >= 0 ? v[b * d + k] : 0.0);
    }
    double f[3] = {0, 0, 0};
    if (rest_length == 0) {
      for (int k = 0; k < d; ++k) f[k] = -stiffness * dx[k] - damping * dv[k];
    } else {
      const double length = std::sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
      if (length == 0) return;  // direction undefined: no force rather than NaN
      const double u[3] = {dx[0] / length, dx[1] / length, dx[2] / length};
      // How fast the spring lengthens (> 0 stretching, < 0 shortening): damping resists it.
      const double stretch_rate = dv[0] * u[0] + dv[1] * u[1] + dv[2] * u[2];
      const double magnitude = -stiffness * (length - rest_length) - damping * stretch_rate;
      for (int k = 0; k < d; ++k) f[k] = magnitude * u[k];
    }
    for (int k = 0; k < d; ++k) {
      F[a * d + k] += f[k];
      if (b >= 0) F[b * d + k] -= f[k];
    }
  }

  double potential(int d, ConstVectorRef x) const {
    double length2 = 0;
    for (int k = 0; k < d; ++k) {
      const double dk = x[a * d + k] - (b >= 0 ? x[b * d + k] : anchor[k]);
      length2 += dk * dk;
    }
    const double stretch = std::sqrt(length2) - rest_length;
    return 0.5 * stiffness * stretch * stretch;
  }
};

}  // namespace motus
