#pragma once
// Uniform gravity: F_i = m_i g on every body. Potential U = −Σ m_i g·x_i.
#include <array>

#include "motus/vector.hpp"

namespace motus {

struct UniformGravity {
  std::array<double, 3> g{0, 0, 0};  // m/s², only the first `d` components are used

  // Masses, X, Forces: Vectors (or Refs), or fixed-size ones (one body: the loops unroll and the
  // numbers stay in registers).
  template <class Masses, class X, class Forces>
  void add_forces(int d, const Masses& m, const X& /*x*/, Forces&& F) const {
    for (Eigen::Index i = 0; i < m.size(); ++i)
      for (int k = 0; k < d; ++k) F[i * d + k] += m[i] * g[k];
  }
  double potential(int d, const Vector& m, ConstVectorRef x) const {
    double u = 0;
    for (Eigen::Index i = 0; i < m.size(); ++i)
      for (int k = 0; k < d; ++k) u -= m[i] * g[k] * x[i * d + k];
    return u;
  }
};

}  // namespace motus
