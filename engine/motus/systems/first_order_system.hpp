#pragma once
// A first-order system y' = f(t, y): the strange attractors, World2, and (through
// MechanicalAsFirstOrder) any mechanical system. This is all the Runge–Kutta
// family ever sees — Witkin & Baraff's "the solver knows nothing of particles".
#include <string>
#include <vector>

#include "motus/vector.hpp"

namespace motus {

class FirstOrderSystem {
public:
  virtual ~FirstOrderSystem() = default;

  // Number of state variables.
  virtual int size() const = 0;
  // dydt = f(t, y). Must not allocate: it is called several times per step.
  virtual void derivative(double t, ConstVectorRef y, VectorRef dydt) = 0;
  // Names of the state variables, for tables and CSV headers.
  virtual std::vector<std::string> variable_names() const;
  // Quantities computed from the state that are worth printing (World2's quality of
  // life, say). Empty by default.
  virtual std::vector<std::string> auxiliary_names() const { return {}; }
  virtual void auxiliaries(double /*t*/, ConstVectorRef /*y*/, VectorRef /*out*/) const {}
  // When a run's state stops being finite: what in the system made it so, if the system can tell
  // (a scene's equations name the first one that gave a NaN or an infinity from a finite state);
  // "" otherwise (then the step is suspect).
  virtual std::string why_not_finite() const { return {}; }

  long evaluations = 0;  // derivative calls so far; every derivative() adds one
};

// What an integrator of the Runge–Kutta family needs from a system. Integrators
// are templates on it so that a concrete, final system is called directly: Simulation
// does so for the built-in attractors and point masses (concrete_system.hpp), while World2
// and a scene's own equations go through FirstOrderSystem, a virtual call per evaluation.
template <class S>
concept FirstOrder = requires(S& s, double t, const Vector& y, Vector& dydt) {
  { s.size() } -> std::convertible_to<int>;
  s.derivative(t, y, dydt);
};

// A system that knows its number of variables at compile time says so with
// `static constexpr int static_size` (the attractors: 3; one body in d dimensions: 2d). An
// integrator then keeps its stages in fixed-size arrays on the stack, which the compiler holds
// in registers, instead of Vectors sized once by resize(); Eigen::Dynamic when it does not.
template <class S>
inline constexpr int static_size_of = Eigen::Dynamic;
template <class S>
  requires requires { S::static_size; }
inline constexpr int static_size_of<S> = S::static_size;

}  // namespace motus
