#pragma once
// Yoshida's (Forest–Ruth's) fourth-order symplectic method: three velocity-Verlet
// substeps of w1 Δt, w0 Δt, w1 Δt with
//   w1 = 1 / (2 − 2^{1/3}),  w0 = −2^{1/3} w1     (w0 + 2 w1 = 1)
// The middle substep runs backwards in time; the errors of the three cancel to
// fourth order. Three force evaluations per step.
#include <cmath>

#include "motus/integrate/velocity_verlet.hpp"

namespace motus {

class Yoshida4 {
public:
  void resize(int n) { verlet_.resize(n); }

  template <Mechanical System>
  void step(System& s, double t, double h, VectorRef x, VectorRef v) {
    static const double w1 = 1 / (2 - std::cbrt(2.0));
    static const double w0 = -std::cbrt(2.0) * w1;
    verlet_.step(s, t, w1 * h, x, v);
    verlet_.step(s, t + w1 * h, w0 * h, x, v);
    verlet_.step(s, t + (w1 + w0) * h, w1 * h, x, v);
  }

private:
  VelocityVerlet verlet_;
};

}  // namespace motus
