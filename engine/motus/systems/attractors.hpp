#pragma once
// The strange attractors of the course (docs/course.md, section 7): three-variable
// first-order systems whose trajectories never settle and never repeat.
// Parameters: docs/course.md and tests/reference/integrators.md; starting points: scenes/.
#include <cmath>

#include "motus/systems/first_order_system.hpp"

namespace motus {

// Each system's formula is its rate(s, d): on any state and derivative read and written by [k] (motus's
// vectors, or Odeint's std::arrays in `motus bench precision`, which is thereby given the same formula).
class ThreeVariableSystem : public FirstOrderSystem {
public:
  static constexpr int static_size = 3;
  int size() const final { return static_size; }
  std::vector<std::string> variable_names() const final { return {"x", "y", "z"}; }
};

// Lorenz (1963): x' = σ(y − x), y' = x(ρ − z) − y, z' = xy − βz
class Lorenz final : public ThreeVariableSystem {
public:
  Lorenz(double sigma = 10, double rho = 28, double beta = 8.0 / 3) : sigma(sigma), rho(rho), beta(beta) {}
  void derivative(double, ConstVectorRef s, VectorRef d) override {
    ++evaluations;
    rate(s, d);
  }
  template <class State, class Rate>
  void rate(const State& s, Rate& d) const {
    const double x = s[0], y = s[1], z = s[2];
    d[0] = sigma * (y - x);
    d[1] = x * (rho - z) - y;
    d[2] = x * y - beta * z;
  }
  double sigma, rho, beta;
};

// Rössler (1976): x' = −y − z, y' = x + a y, z' = b + z (x − c)
class Rossler final : public ThreeVariableSystem {
public:
  Rossler(double a, double b, double c) : a(a), b(b), c(c) {}
  void derivative(double, ConstVectorRef s, VectorRef d) override {
    ++evaluations;
    rate(s, d);
  }
  template <class State, class Rate>
  void rate(const State& s, Rate& d) const {
    const double x = s[0], y = s[1], z = s[2];
    d[0] = -y - z;
    d[1] = x + a * y;
    d[2] = b + z * (x - c);
  }
  double a, b, c;
};

// Chen (1999): x' = a(y − x), y' = (c − a)x − xz + cy, z' = xy − bz
class Chen final : public ThreeVariableSystem {
public:
  Chen(double a, double b, double c) : a(a), b(b), c(c) {}
  void derivative(double, ConstVectorRef s, VectorRef d) override {
    ++evaluations;
    rate(s, d);
  }
  template <class State, class Rate>
  void rate(const State& s, Rate& d) const {
    const double x = s[0], y = s[1], z = s[2];
    d[0] = a * (y - x);
    d[1] = (c - a) * x - x * z + c * y;
    d[2] = x * y - b * z;
  }
  double a, b, c;
};

// Thomas (1999), cyclically symmetric: x' = sin y − bx, y' = sin z − by, z' = sin x − bz
class Thomas final : public ThreeVariableSystem {
public:
  explicit Thomas(double b) : b(b) {}
  void derivative(double, ConstVectorRef s, VectorRef d) override {
    ++evaluations;
    rate(s, d);
  }
  template <class State, class Rate>
  void rate(const State& s, Rate& d) const {
    const double x = s[0], y = s[1], z = s[2];
    d[0] = std::sin(y) - b * x;
    d[1] = std::sin(z) - b * y;
    d[2] = std::sin(x) - b * z;
  }
  double b;
};

// Aizawa: x' = (z − b)x − dy, y' = dx + (z − b)y,
//         z' = c + az − z³/3 − (x² + y²)(1 + ez) + f z x³
class Aizawa final : public ThreeVariableSystem {
public:
  Aizawa(double a, double b, double c, double d, double e, double f) : a(a), b(b), c(c), d(d), e(e), f(f) {}
  void derivative(double, ConstVectorRef s, VectorRef out) override {
    ++evaluations;
    rate(s, out);
  }
  template <class State, class Rate>
  void rate(const State& s, Rate& out) const {
    const double x = s[0], y = s[1], z = s[2];
    out[0] = (z - b) * x - d * y;
    out[1] = d * x + (z - b) * y;
    out[2] = c + a * z - z * z * z / 3 - (x * x + y * y) * (1 + e * z) + f * z * x * x * x;
  }
  double a, b, c, d, e, f;
};

}  // namespace motus
