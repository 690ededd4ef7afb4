#pragma once
// An integrator given from outside (external/external_parts.hpp) as a stepper of the same
// calling shapes as motus's own, so Simulation runs it with the same loop: the system is
// handed over as plain functions on double arrays, and a failure becomes ExternalError.
#include "motus/external/external_parts.hpp"
#include "motus/integrate/step_size_control.hpp"
#include "motus/systems/first_order_system.hpp"
#include "motus/systems/mechanical_system.hpp"

namespace motus {

// What the three shapes below share: the integrator, its name for messages, its state.
class ExternalStepper {
public:
  ExternalStepper(const ExternalIntegrator& integrator, std::string name)
      : integrator_(integrator), name_(std::move(name)) {}

  void resize(int n) {
    x_previous_.resize(n);
    started_ = false;
  }
  void set_tolerance(Tolerance tol) { tol_ = tol; }

  // kExternalFirstOrder
  template <FirstOrder System>
  void step(System& f, double t, double h, VectorRef y) {
    const ExternalFirstOrder view = first_order_view(f);
    check(integrator_.step(integrator_.self, &view, t, h, y.data()));
  }

  // kExternalAdaptive
  template <FirstOrder System>
  bool try_step(System& f, double& t, double& h, VectorRef y) {
    const ExternalFirstOrder view = first_order_view(f);
    int accepted = 0;
    const double h_used = h;
    check(integrator_.try_step(integrator_.self, &view, t, &h, y.data(), tol_.atol, tol_.rtol, &accepted));
    if (!(h > 0)) throw ExternalError(name_ + ": chose a next step of " + std::to_string(h) + " (it must be > 0)");
    if (accepted) t += h_used;
    return accepted != 0;
  }

  // kExternalMechanical and kExternalPositionVerlet
  template <Mechanical System>
  void step(System& s, double t, double h, VectorRef x, VectorRef v) {
    const ExternalMechanical view = mechanical_view(s);
    if (integrator_.kind == kExternalMechanical) {
      check(integrator_.step_mechanical(integrator_.self, &view, t, h, x.data(), v.data()));
      return;
    }
    if (!started_) {
      check(integrator_.verlet_start(integrator_.self, &view, t, h, x.data(), v.data(), x_previous_.data()));
      started_ = true;
    }
    check(integrator_.verlet_step(integrator_.self, &view, t, h, x.data(), x_previous_.data(), v.data()));
    // A velocityless method reports the central difference, as motus's own Verlet does:
    // v_{n+1} = (x_{n+1} − x_n)/h + ½ a_{n+1} h (one more force evaluation per step).
    if (a_.size() != x.size()) a_.resize(x.size());
    s.acceleration(t + h, x, v, a_);
    v = (x - x_previous_) / h + (0.5 * h) * a_;
  }

protected:
  void check(int status) const {
    if (status == 0) return;
    const char* message = integrator_.error ? integrator_.error(integrator_.self) : nullptr;
    throw ExternalCodeFailed(name_ + ": " + (message && *message ? message : "failed"));
  }

  template <class System>
  static ExternalFirstOrder first_order_view(System& f) {
    return {static_cast<int>(f.size()), &f, [](void* self, double t, const double* y, double* dydt) {
              auto& system = *static_cast<System*>(self);
              const Eigen::Index n = system.size();
              system.derivative(t, Eigen::Map<const Vector>(y, n), Eigen::Map<Vector>(dydt, n));
            }};
  }
  template <class System>
  static ExternalMechanical mechanical_view(System& s) {
    return {static_cast<int>(s.size()), &s, [](void* self, double t, const double* x, const double* v, double* a) {
              auto& system = *static_cast<System*>(self);
              const Eigen::Index n = system.size();
              system.acceleration(t, Eigen::Map<const Vector>(x, n), Eigen::Map<const Vector>(v, n),
                                  Eigen::Map<Vector>(a, n));
            }};
  }

  const ExternalIntegrator& integrator_;
  std::string name_;
  Tolerance tol_;
  Vector x_previous_, a_;
  bool started_ = false;
};

// The three calling shapes Simulation knows, one per kind of outside integrator.
class ExternalFixedStep : private ExternalStepper {  // kExternalFirstOrder
public:
  using ExternalStepper::ExternalStepper;
  using ExternalStepper::resize;
  using ExternalStepper::step;
};
class ExternalAdaptiveStep : private ExternalStepper {  // kExternalAdaptive
public:
  using ExternalStepper::ExternalStepper;
  using ExternalStepper::resize;
  using ExternalStepper::set_tolerance;
  using ExternalStepper::try_step;
};
class ExternalMechanicalStep : private ExternalStepper {  // kExternalMechanical, kExternalPositionVerlet
public:
  using ExternalStepper::ExternalStepper;
  using ExternalStepper::resize;
  using ExternalStepper::step;
};

}  // namespace motus
