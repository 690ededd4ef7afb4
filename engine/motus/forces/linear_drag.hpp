#pragma once
// Linear drag on one body, or on every body (body = −1): F = −b v.
// Dissipative, so it has no potential: energy lost to drag is the run's drift.
#include "motus/vector.hpp"

namespace motus {

struct LinearDrag {
  int body = -1;           // −1: every body
  double coefficient = 0;  // b, kg/s

  void add_forces(int d, ConstVectorRef v, VectorRef F) const {
    if (body >= 0) {
      for (int k = 0; k < d; ++k) F[body * d + k] -= coefficient * v[body * d + k];
    } else {
      F -= coefficient * v;
    }
  }
};

}  // namespace motus
