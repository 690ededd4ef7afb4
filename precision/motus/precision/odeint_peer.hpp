#pragma once
// Boost.Odeint as a peer of motus's integrators (docs/peers.md): its steppers on the same
// right-hand side motus integrates, with the state in a std::array when its size is known at
// compile time, else in a std::vector. For Kepler (one body, one central gravity) and Lorenz, the
// right-hand side is written as an Odeint user writes it (a function object with the numbers
// copied in, the same formula: the same errors, steps and evaluations); for every other scene it is
// the scene's system by its concrete type, exactly as Simulation steps it
// (systems/concrete_system.hpp), seen through Eigen maps of the state — which cost Odeint 2–2.5×
// per evaluation on Kepler and 1.15–1.2× on Lorenz (an audit, 2026-12-07; README):
//   odeint:runge_kutta4                   fixed step, the classic RK4
//   odeint:runge_kutta_dopri5             controlled (make_controlled), Dormand–Prince 5(4)
//   odeint:runge_kutta_fehlberg78         controlled, Runge–Kutta–Fehlberg 7(8)
//   odeint:symplectic_rkn_sb3a_mclachlan  fixed step, McLachlan's symplectic RKN of order 4: point
//                                         masses whose forces do not depend on velocities
// A controlled stepper's rtol = atol = tol is in Odeint's own error norm (the largest
// |e_i| / (atol + rtol (|y_i| + h |y'_i|))), not motus's: a tolerance means something else, which is
// why the diagrams set errors reached against work, never tolerances.
#include <string>
#include <vector>

#include "motus/precision/work_precision.hpp"
#include "motus/scene.hpp"

namespace motus::precision {

// Odeint's methods, in the order their curves come (and of their lines in the diagrams).
inline constexpr const char* kOdeintMethods[] = {"runge_kutta4", "runge_kutta_dopri5", "runge_kutta_fehlberg78",
                                                 "symplectic_rkn_sb3a_mclachlan"};

// One curve per Odeint method: fixed-step ones at Sweep::fixed_steps, controlled ones at
// Sweep::tolerances (first step dt). A method that cannot run the scene comes back with
// `unsupported` set.
std::vector<Curve> sweep_odeint(const SceneDescription& scene, const Sweep& sweep);

// "Boost.Odeint, Boost 1.74.0".
std::string odeint_version();

}  // namespace motus::precision
