#pragma once
// A scene's system, its state, and one integrator stepping it: the run loop that
// `motus run`, the benchmarks and the tests share. It builds the system the scene
// describes (a first-order system, or point masses with only the forces the scene
// uses) and dispatches once per run, never per step or per particle.
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "motus/external/external_parts.hpp"
#include "motus/integrate/step_size_control.hpp"
#include "motus/integrate/method.hpp"
#include "motus/scene.hpp"
#include "motus/systems/first_order_system.hpp"
#include "motus/systems/mechanical_system.hpp"
#include "motus/world.hpp"

namespace motus {

// An adaptive integrator's step size fell below what double precision can resolve: the
// tolerance cannot be met (advance() throws it; `motus run` exits 1).
class StepSizeUnderflow : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

struct Energy {
  double kinetic = 0, potential = 0, total = 0;
};

class Simulation {
public:
  // Throws SceneError("integrator", ...) for a symplectic integrator on a first-order
  // system, and SceneError for a scene the engine cannot build (for a description built by hand,
  // a body named as a file names it, bodies[2].position; a force by kind, forces.springs[0].a). `parts` replace the
  // engine's collision response or constraint projection for this run (a plug-in's);
  // what they point at must outlive the Simulation.
  Simulation(const SceneDescription& scene, Method method, ExternalParts parts = {});
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  const SceneDescription& scene() const { return scene_; }
  const Method& method() const { return method_; }
  bool is_mechanical() const { return world_ != nullptr; }

  double time() const { return t_; }
  // The whole state: y for a first-order system, [x; v] for a mechanical one.
  const Vector& state() const { return y_; }
  // Names of the state's entries, for CSV headers ("x0", "vx0", ... or "P", "NR", ...).
  std::vector<std::string> state_names() const;

  // Mechanical systems only (nullopt / empty for first-order ones).
  std::optional<Energy> energy() const;
  Vector momentum() const;
  Vector angular_momentum() const;
  MechanicalSystem* mechanical_system() { return world_ ? &world_->system() : nullptr; }
  const MechanicalSystem* mechanical_system() const { return world_ ? &world_->system() : nullptr; }
  // The world of a mechanical scene (its passes, collision counters, constraint error).
  const World* world() const { return world_.get(); }
  // Whether the scene has sticks (whose error constraint_error() measures).
  bool has_sticks() const { return world_ && world_->has_sticks(); }
  // The largest relative stick-length error now (0 without sticks).
  double constraint_error() const;
  // Whether the scene has pins, and the farthest a pinned body is from its pin now (m).
  bool has_pins() const { return world_ && world_->has_pins(); }
  double pin_error() const;
  FirstOrderSystem* first_order_system() { return first_order_.get(); }
  const FirstOrderSystem* first_order_system() const { return first_order_.get(); }

  // Advance to end_time.
  //   Fixed-step integrators take whole steps of dt: round((end_time − t)/dt) of them when
  //   that lands within 1e-9 of end_time, else one more, so time() may pass end_time by
  //   less than dt. Steps of one dt keep one clock across calls: after k of them from t0,
  //   time() is t0 + k·dt exactly (so advancing to t0 + k·dt one step a call never takes two).
  //   Adaptive ones start from dt (or the step they last chose), pick their own steps
  //   within `tolerance`, and land exactly on end_time.
  // after_step, if given, is called after every accepted step. A part from outside that
  // fails throws ExternalError.
  void advance(double end_time, double dt, Tolerance tolerance,
               const std::function<void(const Simulation&)>& after_step = {});

  long steps() const { return steps_; }
  long rejected() const { return rejected_; }
  long evaluations() const;

private:
  // Throws SceneError when the start's energy or momentum is not a finite number.
  void check_start_is_finite() const;
  struct Stepper;
  SceneDescription scene_;
  Method method_;
  std::unique_ptr<FirstOrderSystem> first_order_;
  std::unique_ptr<World> world_;
  std::unique_ptr<Stepper> stepper_;
  Vector y_;
  double t_ = 0;
  double adaptive_h_ = 0;  // the step an adaptive integrator would like to take next
  // The fixed steps' clock (see advance): t_ is clock_origin_ + clock_steps_ · clock_dt_ while
  // the steps are all of clock_dt_.
  double clock_origin_ = 0, clock_dt_ = 0;
  long clock_steps_ = 0;
  long steps_ = 0, rejected_ = 0;
};

// The number of fixed steps of dt that advance() takes to cover `duration`.
long fixed_step_count(double duration, double dt);

}  // namespace motus
