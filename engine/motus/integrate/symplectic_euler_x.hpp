#pragma once
// Symplectic Euler, the course's second form — position first (docs/course.md, section 4):
//   x_{n+1} = x_n + v_n Δt
//   v_{n+1} = v_n + a_{n+1} Δt
#include "motus/systems/mechanical_system.hpp"

namespace motus {

class SymplecticEulerX {
public:
  void resize(int n) { a_.resize(n); }

  template <Mechanical System>
  void step(System& s, double t, double h, VectorRef x, VectorRef v) {
    x += h * v;
    s.acceleration(t + h, x, v, a_);
    v += h * a_;
  }

private:
  Vector a_;
};

}  // namespace motus
