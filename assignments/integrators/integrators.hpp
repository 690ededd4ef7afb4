#pragma once
// The integrators assignment: the functions you write in integrators.cpp. Each one takes
// one step, as on the course's slides (assignments/integrators/README.md has the formulas).
// motus calls them through the plug-in that plugin.cpp makes of them; you never call them
// yourself, but you may call each other (rk4_doubling_step can use rk4_step).
#include "motus/student/student.hpp"

namespace student {

// ---- Any system y' = f(t, y): call f.derivative(t, y) for f(t, y) ----------------------

// The midpoint method: k1 = f(t, y); k2 = f(t + h/2, y + (h/2) k1); y ← y + h k2.
void midpoint_step(const FirstOrderSystem& f, double t, double h, VectorInOut y);

// Classic fourth-order Runge–Kutta: four slopes, weighted 1/6, 1/3, 1/3, 1/6.
void rk4_step(const FirstOrderSystem& f, double t, double h, VectorInOut y);

// Step doubling ("change Δt as you go"): from y, one RK4 step of h (y_full) and two of h/2
// (y_half). Set error to (y_half − y_full)/15 and return y_half + error (fifth order).
// Do not change anything else; motus accepts or rejects the step from `error`.
Vector rk4_doubling_step(const FirstOrderSystem& f, double t, double h, VectorIn y, Vector& error);

// The step to try next, after a step of h whose error was error_ratio times the
// tolerance (≤ 1: accepted): h · 0.9 · error_ratio^(−1/5), but never more than 5 h nor
// less than h/5.
double next_step_size(double h, double error_ratio);

// ---- Point masses: x'' = a(t, x, v); call s.acceleration(t, x, v) for a -------------------

// Explicit Euler, the course's spring table: a = a(t, x, v); x ← x + h v; v ← v + h a —
// both from the values at the start of the step.
void euler_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v);

// Symplectic Euler, velocity first: v ← v + h a(t, x, v); then x ← x + h v (the new v).
void symplectic_euler_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v);

// Symplectic Euler, position first: x ← x + h v (the old v); then v ← v + h a(t + h, x, v)
// (at the new x).
void symplectic_euler_x_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v);

// Velocity Verlet: v ← v + (h/2) a(t, x, v); x ← x + h v; v ← v + (h/2) a(t + h, x, v).
void velocity_verlet_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v);

// Velocityless Verlet needs x_{−1}, the position one step before the start: return it,
// from x0, v0 and a0 = s.acceleration(t, x0, v0), so that the method keeps its second order.
Vector verlet_start(const MechanicalSystem& s, double t, double h, VectorIn x0, VectorIn v0);

// Velocityless Verlet: x_{n+1} = 2 x_n − x_{n−1} + h² a(t, x_n). On return x holds x_{n+1}
// and x_previous holds x_n. (s.acceleration(t, x): this method keeps no velocities.)
void verlet_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut x_previous);

}  // namespace student
