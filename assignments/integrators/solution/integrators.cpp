// The reference solution of the integrators assignment (for instructors: it scores full
// marks on every public and hidden test). Each function is the slide's formula.
#include "integrators.hpp"

#include <algorithm>
#include <cmath>

namespace student {

void midpoint_step(const FirstOrderSystem& f, double t, double h, VectorInOut y) {
  const Vector k1 = f.derivative(t, y);
  const Vector k2 = f.derivative(t + h / 2, y + (h / 2) * k1);
  y += h * k2;
}

void rk4_step(const FirstOrderSystem& f, double t, double h, VectorInOut y) {
  const Vector k1 = f.derivative(t, y);
  const Vector k2 = f.derivative(t + h / 2, y + (h / 2) * k1);
  const Vector k3 = f.derivative(t + h / 2, y + (h / 2) * k2);
  const Vector k4 = f.derivative(t + h, y + h * k3);
  y += (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4);
}

Vector rk4_doubling_step(const FirstOrderSystem& f, double t, double h, VectorIn y, Vector& error) {
  Vector y_full = y;
  rk4_step(f, t, h, y_full);
  Vector y_half = y;
  rk4_step(f, t, h / 2, y_half);
  rk4_step(f, t + h / 2, h / 2, y_half);
  error = (y_half - y_full) / 15;
  return y_half + error;
}

double next_step_size(double h, double error_ratio) {
  if (error_ratio == 0) return 5 * h;
  return h * std::clamp(0.9 * std::pow(error_ratio, -1.0 / 5), 0.2, 5.0);
}

void euler_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {
  const Vector a = s.acceleration(t, x, v);
  x += h * v;
  v += h * a;
}

void symplectic_euler_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {
  v += h * s.acceleration(t, x, v);
  x += h * v;
}

void symplectic_euler_x_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {
  x += h * v;
  v += h * s.acceleration(t + h, x, v);
}

void velocity_verlet_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {
  v += (h / 2) * s.acceleration(t, x, v);
  x += h * v;
  v += (h / 2) * s.acceleration(t + h, x, v);
}

Vector verlet_start(const MechanicalSystem& s, double t, double h, VectorIn x0, VectorIn v0) {
  return x0 - h * v0 + (h * h / 2) * s.acceleration(t, x0, v0);
}

void verlet_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut x_previous) {
  const Vector x_next = 2 * x - x_previous + (h * h) * s.acceleration(t, x);
  x_previous = x;
  x = x_next;
}

}  // namespace student
