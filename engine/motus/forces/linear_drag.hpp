#pragma once
// Linear drag on one body, or on every body (body = −1): F = −b v.
// Dissipative, so it has no potential: energy lost to drag is the run's drift.
#include "motus/vector.hpp"

namespace motus {

struct LinearDrag {
  int body = -1;           // −1: every body
  double coefficient = 0;  // b, kg/s

  template <class V, class Forces>  // Vectors (or Refs), or fixed-size ones for one body
  void add_forces(int d, const V& v, Forces&& F) const {
    // Every body, or only `body`: a loop whose bound is known at compile time for one body.
    const Eigen::Index bodies = F.size() / d;
    for (Eigen::Index i = 0; i < bodies; ++i) {
      if (body >= 0 && i != body) continue;
      for (int k = 0; k < d; ++k) F[i * d + k] -= coefficient * v[i * d + k];
    }
  }
};

}  // namespace motus
