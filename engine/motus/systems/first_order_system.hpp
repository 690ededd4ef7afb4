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

  long evaluations = 0;  // derivative calls so far; every derivative() adds one
};

// What an integrator of the Runge–Kutta family needs from a system. Integrators
// are templates on it so that a concrete, final system (Lorenz in a benchmark)
// is called directly, while the command line goes through FirstOrderSystem.
template <class S>
concept FirstOrder = requires(S& s, double t, const Vector& y, Vector& dydt) {
  { s.size() } -> std::convertible_to<int>;
  s.derivative(t, y, dydt);
};

}  // namespace motus
