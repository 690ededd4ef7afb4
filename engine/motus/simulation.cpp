#include "motus/simulation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>

#include "motus/huge_pages.hpp"
#include "motus/integrate/dop853.hpp"
#include "motus/integrate/euler.hpp"
#include "motus/integrate/external_stepper.hpp"
#include "motus/integrate/midpoint.hpp"
#include "motus/integrate/rk4.hpp"
#include "motus/integrate/rk45.hpp"
#include "motus/integrate/rk4_doubling.hpp"
#include "motus/integrate/symplectic_euler.hpp"
#include "motus/integrate/symplectic_euler_x.hpp"
#include "motus/integrate/velocity_verlet.hpp"
#include "motus/integrate/verlet.hpp"
#include "motus/integrate/yoshida4.hpp"
#include "motus/message_number.hpp"
#include "motus/scene_error.hpp"
#include "motus/systems/concrete_system.hpp"
#include "motus/systems/system_catalog.hpp"

namespace motus {

// The scene's integrator: one of the engine's, or a plug-in's in one of its three shapes.
struct Simulation::Stepper {
  std::variant<Euler, Midpoint, Rk4, Rk4Doubling, Rk45, Dop853, SymplecticEuler, SymplecticEulerX, Verlet,
               VelocityVerlet, Yoshida4, ExternalFixedStep, ExternalAdaptiveStep, ExternalMechanicalStep>
      chosen;
};

namespace {

// The three calling shapes: step(f, t, h, y); try_step(f, t, h, y); step(s, t, h, x, v).
template <class T>
constexpr bool is_adaptive = std::is_same_v<T, Rk4Doubling> || std::is_same_v<T, Rk45> || std::is_same_v<T, Dop853> ||
                              std::is_same_v<T, ExternalAdaptiveStep>;
template <class T>
constexpr bool is_external = std::is_same_v<T, ExternalFixedStep> || std::is_same_v<T, ExternalAdaptiveStep> ||
                              std::is_same_v<T, ExternalMechanicalStep>;
// The steppers of x and v apart: the symplectic family, and a plug-in's step(x, v) (symplectic or not).
template <class T>
constexpr bool steps_x_and_v = std::is_same_v<T, SymplecticEuler> || std::is_same_v<T, SymplecticEulerX> ||
                               std::is_same_v<T, Verlet> || std::is_same_v<T, VelocityVerlet> ||
                               std::is_same_v<T, Yoshida4> || std::is_same_v<T, ExternalMechanicalStep>;

// A description built by hand (not by the scene loader, which checks all this with the file's
// field paths): what the engine would otherwise read out of bounds. Bodies are named as a scene
// file names them; a force by its kind and place in the ForceSet (forces.springs[0].a), since a
// ForceSet keeps no file's order.
void check_mechanical(const MechanicalDescription& m) {
  if (m.dimensions < 1 || m.dimensions > 3) throw SceneError("dimensions", "must be 1, 2 or 3");
  const auto d = static_cast<size_t>(m.dimensions);
  const int n = static_cast<int>(m.bodies.size());
  for (int i = 0; i < n; ++i) {
    const BodyDescription& b = m.bodies[static_cast<size_t>(i)];
    const std::string at = "bodies[" + std::to_string(i) + "]";
    if (!(b.mass > 0) || !std::isfinite(b.mass)) throw SceneError(at + ".mass", "must be a finite number > 0");
    if (b.position.size() != d)
      throw SceneError(at + ".position", "must have " + std::to_string(d) + " numbers (got " + std::to_string(b.position.size()) + ")");
    if (b.velocity.size() != d)
      throw SceneError(at + ".velocity", "must have " + std::to_string(d) + " numbers (got " + std::to_string(b.velocity.size()) + ")");
  }
  auto body = [n](int i, bool every_allowed, const std::string& field) {
    if ((every_allowed && i == -1) || (i >= 0 && i < n)) return;
    throw SceneError(field, "body " + std::to_string(i) + " does not exist: the scene has bodies 0.." + std::to_string(n - 1));
  };
  // (The loader's forces array lists them in any order; these are by kind.)
  for (size_t f = 0; f < m.forces.springs.size(); ++f) {
    body(m.forces.springs[f].a, false, "forces.springs[" + std::to_string(f) + "].a");
    body(m.forces.springs[f].b, true, "forces.springs[" + std::to_string(f) + "].b");
  }
  for (size_t f = 0; f < m.forces.drag.size(); ++f) body(m.forces.drag[f].body, true, "forces.drag[" + std::to_string(f) + "].body");
  for (size_t f = 0; f < m.forces.central_gravity.size(); ++f)
    body(m.forces.central_gravity[f].body, true, "forces.central_gravity[" + std::to_string(f) + "].body");
  for (size_t f = 0; f < m.forces.pendulums.size(); ++f)
    body(m.forces.pendulums[f].body, false, "forces.pendulums[" + std::to_string(f) + "].body");
}

}  // namespace

long fixed_step_count(double duration, double dt) {
  const double steps = duration / dt;
  // Beyond 2^62 a count is not a long, and long before that t0 + i·dt is not exact: refuse
  // rather than convert an oversized double (undefined behaviour) into a wrong count.
  if (!(steps >= 0) || !(steps < 4.6e18))
    throw std::overflow_error("a duration of " + std::to_string(duration) + " at dt = " + std::to_string(dt) +
                              " is more steps than can be counted");
  const double nearest = std::round(steps);
  if (std::abs(nearest - steps) <= 1e-9 * std::max(1.0, steps)) return static_cast<long>(nearest);
  return static_cast<long>(std::ceil(steps));
}

Simulation::Simulation(const SceneDescription& scene, Method method, ExternalParts parts)
    : scene_(scene), method_(std::move(method)), stepper_(std::make_unique<Stepper>()), t_(scene.start_time) {
  if (scene.mechanical) {
    const auto& m = *scene.mechanical;
    check_mechanical(m);
    const int n = static_cast<int>(m.bodies.size()) * m.dimensions;
    y_.resize(2 * n);
    // (Before its first touch: the state of 10^6 balls, read in the collision grid's order, on huge
    // pages. Eigen takes it from malloc, which maps a block this big fresh from the kernel — above its
    // threshold, 128 kB and after big frees up to 32 MB; a block it hands out again keeps its pages.)
    advise_huge_pages(y_.data(), sizeof(double) * static_cast<size_t>(y_.size()));
    for (size_t i = 0; i < m.bodies.size(); ++i) {
      for (int k = 0; k < m.dimensions; ++k) {
        y_[static_cast<Eigen::Index>(i) * m.dimensions + k] = m.bodies[i].position[k];
        y_[n + static_cast<Eigen::Index>(i) * m.dimensions + k] = m.bodies[i].velocity[k];
      }
    }
    world_ = std::make_unique<World>(m, method_, parts);  // throws if the integrator cannot run its passes
    check_start_is_finite();
  } else if (scene.first_order) {
    if (scene.first_order->make) {
      first_order_ = scene.first_order->make();  // e.g. the scene file's "equations"
      if (!first_order_) throw SceneError("system", "the system could not be made");
    } else {
      const SystemInfo* info = find_first_order_system(scene.first_order->type);
      if (!info) throw SceneError("system.type", "unknown system \"" + scene.first_order->type + "\"");
      // The catalog's defaults for what a description built by hand leaves out (the loader fills
      // them in); a name the system does not have is an error, as in a file.
      std::map<std::string, double> parameters;
      for (const auto& p : info->parameters) parameters[p.name] = p.default_value;
      for (const auto& [name, value] : scene.first_order->parameters) {
        if (!parameters.count(name)) throw SceneError("system.parameters." + name, "unknown parameter of " + info->type);
        parameters[name] = value;
      }
      first_order_ = info->make(parameters);
    }
    const auto& init = scene.first_order->initial;
    if (static_cast<int>(init.size()) != first_order_->size())
      throw SceneError("system.initial", "needs " + std::to_string(first_order_->size()) + " numbers (" +
                                             std::to_string(init.size()) + " given)");
    y_ = Eigen::Map<const Vector>(init.data(), static_cast<Eigen::Index>(init.size()));
  } else {
    throw SceneError("", "a scene needs either \"bodies\" (mechanical) or \"system\" (first-order)");
  }

  if (method_.needs_mechanical() && !world_)
    throw SceneError("integrator", method_.name() +
                                       (method_.is_external() ? " steps bodies (x and v)" : " is symplectic") +
                                       ": it needs a mechanical scene (bodies), and this scene is the "
                                       "first-order system \"" + scene.first_order->type +
                                       "\"; use " + first_order_integrator_names());

  auto& chosen = stepper_->chosen;
  if (method_.is_external()) {
    switch (method_.outside().kind) {
      case kExternalFirstOrder: chosen.emplace<ExternalFixedStep>(method_.outside(), method_.name()); break;
      case kExternalAdaptive: chosen.emplace<ExternalAdaptiveStep>(method_.outside(), method_.name()); break;
      case kExternalMechanical:
      case kExternalPositionVerlet: chosen.emplace<ExternalMechanicalStep>(method_.outside(), method_.name()); break;
      default: throw SceneError("integrator", method_.name() + ": unknown kind of integrator");
    }
  } else {
    switch (method_.builtin()) {
      case Integrator::Euler: chosen.emplace<Euler>(); break;
      case Integrator::Midpoint: chosen.emplace<Midpoint>(); break;
      case Integrator::Rk4: chosen.emplace<Rk4>(); break;
      case Integrator::Rk4Doubling: chosen.emplace<Rk4Doubling>(); break;
      case Integrator::Rk45: chosen.emplace<Rk45>(); break;
      case Integrator::Dop853: chosen.emplace<Dop853>(); break;
      case Integrator::SymplecticEuler: chosen.emplace<SymplecticEuler>(); break;
      case Integrator::SymplecticEulerX: chosen.emplace<SymplecticEulerX>(); break;
      case Integrator::Verlet: chosen.emplace<Verlet>(); break;
      case Integrator::VelocityVerlet: chosen.emplace<VelocityVerlet>(); break;
      case Integrator::Yoshida4: chosen.emplace<Yoshida4>(); break;
    }
  }
  // Mechanical steppers work on x (or v): half the state. The rest work on all of it.
  const int n = static_cast<int>(y_.size());
  std::visit(
      [&](auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (steps_x_and_v<S>)
          s.resize(n / 2);
        else
          s.resize(n);
      },
      chosen);
}

Simulation::~Simulation() = default;

long Simulation::evaluations() const {
  return world_ ? world_->system().evaluations : first_order_->evaluations;
}

void Simulation::advance(double end_time, double dt, Tolerance tolerance,
                         const std::function<void(const Simulation&)>& after_step) {
  if (!(dt > 0)) throw std::invalid_argument("dt must be > 0");
  if (!(end_time > t_)) return;

  auto run = [&](auto& stepper, auto& system) {
    using S = std::decay_t<decltype(stepper)>;
    if constexpr (is_adaptive<S>) {
      stepper.set_tolerance(tolerance);
      if (adaptive_h_ <= 0) adaptive_h_ = dt;
      while (t_ < end_time) {
        double h = std::min(adaptive_h_, end_time - t_);
        const bool landing = h < adaptive_h_;  // shortened to land on end_time
        const double tried = h;
        const bool accepted = stepper.try_step(system, t_, h, y_);
        // A step cut short to land on end_time says nothing of the step the error allows: after
        // it is accepted the step chosen before is kept, so that the next advance() does not start
        // small. (Rejected, even a landing step's shrunk h is what the error asks for.)
        if (!landing || !accepted) adaptive_h_ = h;
        if (!accepted) {
          ++rejected_;
          // A controller that does not shrink a rejected step (a student's that keeps h, say)
          // would try the same step for ever.
          if (std::isnan(adaptive_h_)) {
            // (A scene's equation that gave a NaN says so: FirstOrderSystem::why_not_finite.)
            const std::string why = first_order_ ? first_order_->why_not_finite() : std::string();
            throw StepSizeUnderflow("the step-size control proposed no number after a rejected step at t = " + message_number(t_) +
                                     " (" + (why.empty() ? "an error estimate that is not finite?" : why) + ")");
          }
          if (!(adaptive_h_ < tried))
            throw StepSizeUnderflow("the step-size control did not shrink a rejected step at t = " + message_number(t_) +
                                     " (h = " + message_number(tried) + " was rejected, and " + message_number(adaptive_h_) +
                                     " came next): it would be tried for ever");
          if (adaptive_h_ < 1e-14 * std::max(1.0, std::abs(t_)))
            throw StepSizeUnderflow("step size underflow at t = " + message_number(t_) +
                                     ": the tolerance cannot be met in double precision");
          continue;
        }
        if (landing) t_ = end_time;  // exactly, whatever t + h rounded to
        // A controller that shrinks accepted steps too (a student's, say) may never reach the end:
        // its steps' sum can stay below it for ever.
        if (!(adaptive_h_ >= 1e-14 * std::max(1.0, std::abs(t_))) && t_ < end_time)
          throw StepSizeUnderflow("step size underflow at t = " + message_number(t_) + ": the step-size control proposed h = " +
                                   message_number(adaptive_h_) + " after an accepted step (a step size that shrinks without end?)");
        ++steps_;
        if (after_step) after_step(*this);
      }
    } else {
      // One clock across calls: time is origin + k·dt, k the steps of this dt since the clock was
      // set (at the start, or after a step of another kind or size). A caller that steps to
      // t0 + k·dt one call at a time (compare's backend, a loop over frames) lands on exactly its
      // times; summed call by call, t + dt would drift by a rounding each time, and after about
      // 10^4 calls the gap passes fixed_step_count's 1e-9 and one call takes two steps.
      if (dt != clock_dt_ || t_ != clock_origin_ + static_cast<double>(clock_steps_) * clock_dt_)
        clock_origin_ = t_, clock_steps_ = 0, clock_dt_ = dt;
      const long n = std::max(0L, fixed_step_count(end_time - clock_origin_, dt) - clock_steps_);
      const double t0 = clock_origin_;
      const long k0 = clock_steps_;
      const long steps0 = steps_;
      const Eigen::Index half = y_.size() / 2;
      // x and v as views into the state, made once: a step then passes them on as they are.
      Eigen::Map<Vector> x(y_.data(), half), v(y_.data() + half, half);
      double t = t_;  // local, so the loop keeps it in a register
      try {
        for (long i = 0; i < n; ++i) {
          if constexpr (!steps_x_and_v<S>) {
            stepper.step(system, t, dt, y_);
          } else {
            world_->step(stepper, t, dt, x, v);
          }
          t = t0 + static_cast<double>(k0 + i + 1) * dt;  // no drift from adding dt a million times
          if (after_step) {
            t_ = t;
            steps_ = steps0 + i + 1;
            after_step(*this);
          }
        }
      } catch (const ExternalError&) {
        // (The step a plug-in's part failed in, for the message below: t and the count are kept
        // only in the loop.)
        t_ = t;
        steps_ = steps0 + std::lround((t - t0) / dt) - k0;
        throw;
      }
      t_ = t;
      steps_ = steps0 + n;
      clock_steps_ = k0 + n;
    }
  };

  // A plug-in's part that fails says where in the run: "returned 0 as the time of impact of ..."
  // alone did not tell a student the first contact from the thousandth. (Its type is kept: the
  // grader tells the code's own failure from numbers refused.)
  const auto when = [&] { return " (in step " + std::to_string(steps_ + 1) + ", from t = " + message_number(t_) + ")"; };
  try {
    std::visit(
        [&](auto& stepper) {
          using S = std::decay_t<decltype(stepper)>;
          if constexpr (steps_x_and_v<S>) {
            run(stepper, world_->system());
          } else if constexpr (is_external<S>) {  // plain functions on arrays: nothing to inline
            if (world_) {
              MechanicalAsFirstOrder as_first_order(world_->system());
              run(stepper, as_first_order);
            } else {
              run(stepper, *first_order_);
            }
          } else if (world_) {
            // The system by its concrete type (systems/concrete_system.hpp): direct calls, and
            // for one body or an attractor stages of a size known at compile time.
            with_first_order_view(world_->system(), [&](auto& f) { run(stepper, f); });
          } else {
            with_concrete_system(*first_order_, [&](auto& f) { run(stepper, f); });
          }
        },
        stepper_->chosen);
  } catch (const ExternalCodeFailed& e) {
    throw ExternalCodeFailed(e.what() + when());
  } catch (const ExternalError& e) {
    throw ExternalError(e.what() + when());
  }
}

std::vector<std::string> Simulation::state_names() const {
  if (!world_) return first_order_->variable_names();
  static const char* axes[] = {"x", "y", "z"};
  std::vector<std::string> names;
  const int d = world_->system().dimensions();
  for (const char* prefix : {"", "v"})
    for (int i = 0; i < world_->system().particles(); ++i)
      for (int k = 0; k < d; ++k) names.push_back(std::string(prefix) + axes[k] + std::to_string(i));
  return names;
}

void Simulation::check_start_is_finite() const {
  // Each body's own ½ m |v|² is checked by the loader, but sums of finite terms can pass the
  // largest double (two bodies of 1e308 kg), and so can a potential (1e307 kg, 100 m up): every
  // energy the run reported was then infinite from the start, and compare said motus had blown up.
  const Energy e = *energy();
  const Vector p = momentum();
  if (!std::isfinite(e.kinetic) || !p.allFinite())
    throw SceneError("bodies", "the bodies' kinetic energy or momentum together is past the largest double (1.8e308) "
                               "at the start: masses or speeds too large");
  if (!std::isfinite(e.potential) || !std::isfinite(e.total))
    throw SceneError("forces", "the potential energy at the start is not a finite number (" +
                                   message_number(e.potential, 3) +
                                   " J): masses, distances or forces too large for a double");
}

std::optional<Energy> Simulation::energy() const {
  if (!world_) return std::nullopt;
  const int n = world_->system().size();
  Energy e;
  e.kinetic = world_->system().kinetic_energy(y_.tail(n));
  e.potential = world_->system().potential_energy(y_.head(n));
  e.total = e.kinetic + e.potential;
  return e;
}

double Simulation::constraint_error() const {
  return world_ ? world_->constraint_error(y_.head(world_->system().size())) : 0.0;
}

double Simulation::pin_error() const { return world_ ? world_->pin_error(y_.head(world_->system().size())) : 0.0; }

Vector Simulation::momentum() const {
  if (!world_) return Vector(0);
  return world_->system().momentum(y_.tail(world_->system().size()));
}

Vector Simulation::angular_momentum() const {
  if (!world_) return Vector(0);
  const int n = world_->system().size();
  return world_->system().angular_momentum(y_.head(n), y_.tail(n));
}

}  // namespace motus
