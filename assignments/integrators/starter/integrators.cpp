// The integrators assignment: write each function below (the formulas are in
// assignments/integrators/README.md and above each declaration in integrators.hpp).
// Build and run the public tests with one command, from the folder motus was built in:
//   build/motus grade integrators THIS_FOLDER
#include "integrators.hpp"

#include <algorithm>
#include <cmath>

namespace student {

void midpoint_step(const FirstOrderSystem& f, double t, double h, VectorInOut y) {
  // TODO: k1 = f(t, y); k2 = f(t + h/2, y + (h/2) k1); y ← y + h k2
  (void)f, (void)t, (void)h, (void)y;
}

void rk4_step(const FirstOrderSystem& f, double t, double h, VectorInOut y) {
  // TODO: k1 … k4, then y ← y + h (k1 + 2 k2 + 2 k3 + k4) / 6
  (void)f, (void)t, (void)h, (void)y;
}

Vector rk4_doubling_step(const FirstOrderSystem& f, double t, double h, VectorIn y, Vector& error) {
  // TODO: y_full = one RK4 step of h; y_half = two of h/2; error = (y_half − y_full)/15;
  // return y_half + error.
  (void)f, (void)t, (void)h;
  error = Vector::Zero(y.size());
  return y;
}

double next_step_size(double h, double error_ratio) {
  // TODO: h · 0.9 · error_ratio^(−1/5), kept between h/5 and 5 h
  (void)error_ratio;
  return h;
}

void euler_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {
  // TODO: a = s.acceleration(t, x, v); then x ← x + h v and v ← v + h a (the values from the start)
  (void)s, (void)t, (void)h, (void)x, (void)v;
}

void symplectic_euler_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {
  // TODO: v ← v + h a(t, x, v); then x ← x + h v
  (void)s, (void)t, (void)h, (void)x, (void)v;
}

void symplectic_euler_x_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {
  // TODO: x ← x + h v; then v ← v + h a(t + h, x, v)
  (void)s, (void)t, (void)h, (void)x, (void)v;
}

void velocity_verlet_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {
  // TODO: half a kick, a drift, half a kick
  (void)s, (void)t, (void)h, (void)x, (void)v;
}

Vector verlet_start(const MechanicalSystem& s, double t, double h, VectorIn x0, VectorIn v0) {
  // TODO: x_{−1} = x0 − h v0 + (h²/2) a0, with a0 = s.acceleration(t, x0, v0)
  (void)s, (void)t, (void)h, (void)v0;
  return x0;
}

void verlet_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut x_previous) {
  // TODO: x_next = 2 x − x_previous + h² a(t, x); then x_previous ← x and x ← x_next
  (void)s, (void)t, (void)h, (void)x, (void)x_previous;
}

}  // namespace student
