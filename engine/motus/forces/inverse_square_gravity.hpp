#pragma once
// Inverse-square gravity with optional (Plummer) softening ε:
//   about a fixed centre:  F_i = −μ m_i r / (|r|² + ε²)^{3/2},   U = −μ m_i / √(|r|² + ε²)
//   mutual, every pair:    F_i = −G m_i m_j r_ij / (|r_ij|² + ε²)^{3/2},  U = −G m_i m_j / √(|r_ij|² + ε²)
// (μ = G M is the centre's gravitational parameter; Kepler's problem has μ = 1.)
#include <array>
#include <cmath>

#include "motus/vector.hpp"

namespace motus {

struct CentralGravity {
  int body = -1;  // −1: every body
  std::array<double, 3> centre{0, 0, 0};
  double mu = 1;
  double softening = 0;

  // Masses, X, Forces: Vectors (or Refs), or fixed-size ones (one body: the loops unroll and the
  // numbers stay in registers).
  template <class Masses, class X, class Forces>
  void add_forces(int d, const Masses& m, const X& x, Forces&& F) const {
    // Every body, or only `body`: a loop whose bound is known at compile time for one body.
    for (Eigen::Index i = 0; i < m.size(); ++i) {
      if (body >= 0 && i != body) continue;
      double r[3] = {0, 0, 0};
      for (int k = 0; k < d; ++k) r[k] = x[i * d + k] - centre[k];
      // |r|² + ε², leaving out the terms that are exactly 0 (the same sum, fewer additions).
      double s2 = r[0] * r[0];
      for (int k = 1; k < d; ++k) s2 += r[k] * r[k];
      if (softening != 0) s2 += softening * softening;
      const double scale = -mu * m[i] / (s2 * std::sqrt(s2));
      for (int k = 0; k < d; ++k) F[i * d + k] += scale * r[k];
    }
  }
  double potential(int d, const Vector& m, ConstVectorRef x) const {
    double u = 0;
    const Eigen::Index first = body >= 0 ? body : 0, last = body >= 0 ? body + 1 : m.size();
    for (Eigen::Index i = first; i < last; ++i) {
      double s2 = softening * softening;
      for (int k = 0; k < d; ++k) s2 += (x[i * d + k] - centre[k]) * (x[i * d + k] - centre[k]);
      u -= mu * m[i] / std::sqrt(s2);
    }
    return u;
  }
};

struct MutualGravity {
  double G = 1;
  double softening = 0;

  template <class Masses, class X, class Forces>  // Vectors (or Refs), or fixed-size ones for one body
  void add_forces(int d, const Masses& m, const X& x, Forces&& F) const {
    for (Eigen::Index i = 0; i < m.size(); ++i)
      for (Eigen::Index j = i + 1; j < m.size(); ++j) {
        double r[3] = {0, 0, 0};
        for (int k = 0; k < d; ++k) r[k] = x[i * d + k] - x[j * d + k];
        const double s2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2] + softening * softening;
        const double scale = -G * m[i] * m[j] / (s2 * std::sqrt(s2));
        for (int k = 0; k < d; ++k) {
          F[i * d + k] += scale * r[k];
          F[j * d + k] -= scale * r[k];
        }
      }
  }
  double potential(int d, const Vector& m, ConstVectorRef x) const {
    double u = 0;
    for (Eigen::Index i = 0; i < m.size(); ++i)
      for (Eigen::Index j = i + 1; j < m.size(); ++j) {
        double s2 = softening * softening;
        for (int k = 0; k < d; ++k) s2 += (x[i * d + k] - x[j * d + k]) * (x[i * d + k] - x[j * d + k]);
        u -= G * m[i] * m[j] / std::sqrt(s2);
      }
    return u;
  }
};

}  // namespace motus
