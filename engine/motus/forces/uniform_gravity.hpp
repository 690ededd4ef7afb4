#pragma once
// Uniform gravity: F_i = m_i g on every body. Potential U = −Σ m_i g·x_i.
#include <array>

#include "motus/vector.hpp"

namespace motus {

struct UniformGravity {
  std::array<double, 3> g{0, 0, 0};  // m/s², only the first `d` components are used

  void add_forces(int d, const Vector& m, ConstVectorRef /*x*/, VectorRef F) const {
    switch (d) {  // (the dimension known to the compiler: no loop of d per body)
      case 1: add_forces_in<1>(m, F); break;
      case 2: add_forces_in<2>(m, F); break;
      default: add_forces_in<3>(m, F); break;
    }
  }
  template <int D>
  void add_forces_in(const Vector& m, VectorRef F) const {
    for (Eigen::Index i = 0; i < m.size(); ++i)
      for (int k = 0; k < D; ++k) F[i * D + k] += m[i] * g[k];
  }
  double potential(int d, const Vector& m, ConstVectorRef x) const {
    double u = 0;
    for (Eigen::Index i = 0; i < m.size(); ++i)
      for (int k = 0; k < d; ++k) u -= m[i] * g[k] * x[i * d + k];
    return u;
  }
};

}  // namespace motus
