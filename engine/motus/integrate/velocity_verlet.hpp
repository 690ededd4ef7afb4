#pragma once
// Velocity Verlet ("kick, drift, kick"):
//   v_{n+½} = v_n + ½ a_n Δt
//   x_{n+1} = x_n + v_{n+½} Δt
//   v_{n+1} = v_{n+½} + ½ a_{n+1} Δt
// The same positions as velocityless Verlet, with velocities. a_{n+1} is kept for
// the next step, so one force evaluation per step. Second order; on x'' = −ω²x it
// keeps ½(v² + ω²(1 − ω²Δt²/4) x²) exactly. A force that depends on velocity (drag,
// a damped spring) sees v_{n+½} in a_{n+1} = a(x_{n+1}, v_{n+½}): v_{n+1} is not known
// until a_{n+1} is (the slide's formula assumes forces of position alone).
#include "motus/systems/mechanical_system.hpp"

namespace motus {

class VelocityVerlet {
public:
  void resize(int n) {
    a_.resize(n);
    have_acceleration_ = false;
  }

  template <Mechanical System>
  void step(System& s, double t, double h, VectorRef x, VectorRef v) {
    if (!have_acceleration_) {
      s.acceleration(t, x, v, a_);
      have_acceleration_ = true;
    }
    v += (0.5 * h) * a_;
    x += h * v;
    s.acceleration(t + h, x, v, a_);  // (v is v_{n+½} here)
    v += (0.5 * h) * a_;
  }

private:
  Vector a_;
  bool have_acceleration_ = false;
};

}  // namespace motus
