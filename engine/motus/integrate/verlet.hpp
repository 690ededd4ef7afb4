#pragma once
// Velocityless (Störmer) Verlet, as docs/course.md (section 4) derives it:
//   x_{n+1} = 2 x_n − x_{n−1} + a_n Δt²
// It needs x_{n−1} to start. The derivation's v_n Δt ≈ x_n − x_{n−1} would give
// x_{−1} = x_0 − v_0 Δt, which makes the method first order; the Taylor start
//   x_{−1} = x_0 − v_0 Δt + ½ a_0 Δt²
// keeps it second order.
// Velocities are not part of the method. We report the central difference
//   v_{n+1} = (x_{n+2} − x_n) / 2Δt = (x_{n+1} − x_n)/Δt + ½ a_{n+1} Δt,
// using a_{n+1}, which the next step needs anyway: one force evaluation per step.
// (a_{n+1} is taken before v_{n+1} is known: a velocity-dependent force such as drag sees v_n,
// a step old. In a scene that projects its positions, World reports (x_{n+1} − x_n)/Δt instead:
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
  // Whether x_{n−1} is known (the first step takes it from x and v).
  bool started() const { return started_; }
  // x_n after a step (x_{n+1} is the state's x): a world that moves x by projection
  // (constraints, walls) reads the velocity from the two, as Jakobsen's Verlet does.
  const Vector& previous_positions() const { return x_previous_; }
  // Take a_{n+1} again after x was moved from outside (the next step uses it).
  template <Mechanical System>
  void refresh_acceleration(System& s, double t, ConstVectorRef x, ConstVectorRef v) {
    s.acceleration(t, x, v, a_);
  }

  template <Mechanical System>
  void step(System& s, double t, double h, VectorRef x, VectorRef v) {
    move(s, t, h, x, v);
    s.acceleration(t + h, x, v, a_);
    v = (x - x_previous_) / h + (0.5 * h) * a_;
  }

  // The step's positions alone, x_{n+1} = 2 x_n − x_{n−1} + a_n Δt²: for a world that projects
  // them, then reads the velocity from them and takes a_{n+1} itself where the forces can change
  // it (world.hpp; refresh_acceleration). What step() adds to it would be thrown away there.
  template <Mechanical System>
  void move(System& s, double t, double h, VectorRef x, ConstVectorRef v) {
    if (!started_) {
      s.acceleration(t, x, v, a_);
      x_previous_ = x - h * v + (0.5 * h * h) * a_;
      started_ = true;
    }
    // x_{n+1} = 2 x_n − x_{n−1} + a_n Δt², and x_n becomes the previous position: one pass.
    const double h2 = h * h;
    double* x_next = x.data();  // (holds x_n until it is overwritten with x_{n+1})
    double* x_previous = x_previous_.data();
    const double* a = a_.data();
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      const double x_n = x_next[i];
      x_next[i] = (2 * x_n - x_previous[i]) + h2 * a[i];
      x_previous[i] = x_n;
    }
  }

private:
  Vector a_, x_previous_;
  bool started_ = false;
};

}  // namespace motus
