#pragma once
// Velocityless (Störmer) Verlet, as docs/course.md (section 4) derives it:
//   p_{n+1} = 2 p_n − p_{n−1} + a_n Δt²
// It needs p_{n−1} to start. The derivation's v_n Δt ≈ p_n − p_{n−1} would give
// p_{−1} = p_0 − v_0 Δt, which makes the method first order; the Taylor start
//   p_{−1} = p_0 − v_0 Δt + ½ a_0 Δt²
// keeps it second order.
// Velocities are not part of the method. We report the central difference
//   v_{n+1} = (p_{n+2} − p_n) / 2Δt = (p_{n+1} − p_n)/Δt + ½ a_{n+1} Δt,
// using a_{n+1}, which the next step needs anyway: one force evaluation per step.
// (a_{n+1} is taken before v_{n+1} is known: a velocity-dependent force such as drag sees v_n,
// a step old. In a scene that projects its positions, World reports (p_{n+1} − p_n)/Δt instead:
// see world.hpp.)
#include "motus/systems/mechanical_system.hpp"

namespace motus {

class Verlet {
public:
  void resize(int n) {
    a_.resize(n);
    x_previous_.resize(n);
    started_ = false;
  }
  // Forget p_{n−1} (call after changing x or v from outside).
  void reset() { started_ = false; }
  // Whether p_{n−1} is known (the first step takes it from x and v).
  bool started() const { return started_; }
  // p_n after a step (p_{n+1} is the state's x): a world that moves x by projection
  // (constraints, walls) reads the velocity from the two, as Jakobsen's Verlet does.
  const Vector& previous_positions() const { return x_previous_; }
  // Take a_{n+1} again after x was moved from outside (the next step uses it).
  template <Mechanical System>
  void refresh_acceleration(System& s, double t, ConstVectorRef x, ConstVectorRef v) {
    s.acceleration(t, x, v, a_);
  }

  template <Mechanical System>
  void step(System& s, double t, double h, VectorRef x, VectorRef v) {
    if (!started_) {
      s.acceleration(t, x, v, a_);
      x_previous_ = x - h * v + (0.5 * h * h) * a_;
      started_ = true;
    }
    // p_{n+1} = 2 p_n − p_{n−1} + a_n Δt², and p_n becomes the previous position: one pass.
    const double h2 = h * h;
    double* p = x.data();
    double* p_previous = x_previous_.data();
    const double* a = a_.data();
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double p_n = p[i];
      p[i] = (2 * p_n - p_previous[i]) + h2 * a[i];
      p_previous[i] = p_n;
    }
    s.acceleration(t + h, x, v, a_);
    v = (x - x_previous_) / h + (0.5 * h) * a_;
  }

private:
  Vector a_, x_previous_;
  bool started_ = false;
};

}  // namespace motus
