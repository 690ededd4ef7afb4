#pragma once
// Symplectic (semi-implicit) Euler, the course's first form — velocity first
// (docs/course.md, section 4):
//   v_{n+1} = v_n + a_n Δt
//   x_{n+1} = x_n + v_{n+1} Δt
// First order, but on x'' = −ω²x it keeps ½(v² + ω²x² − ω²Δt·x·v) exactly, so the
// energy wobbles and never drifts. Box2D and Bullet integrate this way.
#include "motus/systems/mechanical_system.hpp"

namespace motus {

class SymplecticEuler {
public:
  void resize(int n) { a_.resize(n); }

  template <Mechanical System>
  void step(System& s, double t, double h, VectorRef x, VectorRef v) {
    kick(s, t, h, x, v);
    drift(h, x, v);
  }

  // The two halves, for a world that replaces the straight-line drift with one that
  // stops at every collision (collide/ball_collisions.hpp).
  template <Mechanical System>
  void kick(System& s, double t, double h, ConstVectorRef x, VectorRef v) {
    s.acceleration(t, x, v, a_);
    v += h * a_;
  }
  static void drift(double h, VectorRef x, ConstVectorRef v) { x += h * v; }

private:
  Vector a_;
};

}  // namespace motus
