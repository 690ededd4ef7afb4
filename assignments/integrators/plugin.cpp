// The integrators assignment as a motus plug-in: your functions (integrators.cpp) under the
// names `motus --integrator` takes, prefixed "student:". This file is the assignment's; the
// grader uses its own copy, so there is nothing to change here.
#include "integrators.hpp"
#include "motus/student/plugin.hpp"

MOTUS_PLUGIN("student", "the integrators assignment (integrators.cpp)") {
  plugin.mechanical("euler", 1, "explicit Euler: x += h v; v += h a (both from the start of the step)",
                    student::euler_step);
  plugin.first_order("midpoint", 2, "midpoint (RK2)", student::midpoint_step);
  plugin.first_order("rk4", 4, "classic fourth-order Runge-Kutta", student::rk4_step);
  plugin.adaptive("rk4-doubling", 5, "adaptive RK4 by step doubling", student::rk4_doubling_step,
                  student::next_step_size);
  plugin.mechanical("symplectic-euler", 1, "symplectic Euler, velocity first", student::symplectic_euler_step);
  plugin.mechanical("symplectic-euler-x", 1, "symplectic Euler, position first", student::symplectic_euler_x_step);
  plugin.mechanical("velocity-verlet", 2, "velocity Verlet: kick, drift, kick", student::velocity_verlet_step);
  plugin.position_verlet("verlet", 2, "velocityless Verlet", student::verlet_start, student::verlet_step);
}
