#pragma once
// Making a motus plug-in of a student's functions. An assignment's plugin.cpp (not the
// student's to edit) says which function is which part:
//
//   #include "motus/student/plugin.hpp"
//   #include "integrators.hpp"
//   MOTUS_PLUGIN("student", "the course's integrators, written by a student") {
//     plugin.first_order("midpoint", 2, "midpoint (RK2)", student::midpoint_step);
//     plugin.mechanical("symplectic-euler", 1, "v += a h; x += v h", student::symplectic_euler_step);
//   }
//
// and this header turns them into the one entry point motus loads (motus/plugin/plugin_abi.hpp).
// Every call from motus goes through a small function here that hands the student plain
// vectors and turns anything the student's code throws into a one-line error for motus.
#include <cxxabi.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>
#include <typeinfo>
#include <vector>

#include "motus/plugin/plugin_abi.hpp"
#include "motus/student/constraints.hpp"
#include "motus/student/student.hpp"

namespace student {

// The student's functions, by shape.
using FirstOrderStep = void (*)(const FirstOrderSystem& f, double t, double h, VectorInOut y);
using MechanicalStep = void (*)(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v);
using VerletStart = Vector (*)(const MechanicalSystem& s, double t, double h, VectorIn x0, VectorIn v0);
using VerletStep = void (*)(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut x_previous);
using StepWithError = Vector (*)(const FirstOrderSystem& f, double t, double h, VectorIn y, Vector& error);
using DoublingStep [[deprecated("use StepWithError")]] = StepWithError;  // (its old name, still accepted)
using NextStepSize = double (*)(double h, double error_ratio);

struct CollisionFunctions {
  void (*collide_balls)(double m_a, VectorInOut v_a, double m_b, VectorInOut v_b, VectorIn n, double e);
  void (*bounce_off_wall)(VectorInOut v, VectorIn n, double e);
  double (*time_of_impact)(VectorIn p_a, VectorIn v_a, double r_a, VectorIn p_b, VectorIn v_b, double r_b);
  double (*time_of_impact_with_plane)(VectorIn p, VectorIn v, double r, VectorIn n, double offset);
};
using SatisfyConstraints = void (*)(Bodies& bodies, const Constraints& constraints);

namespace detail {

inline std::string& last_error() {
  thread_local std::string message;
  return message;
}
inline const char* error(void*) {
  return last_error().empty() ? "ran out of memory (std::bad_alloc, while saying what went wrong)" : last_error().c_str();
}

// "std::out_of_range", not "St12out_of_range".
inline std::string type_name(const std::type_info& type) {
  int status = 0;
  char* readable = abi::__cxa_demangle(type.name(), nullptr, nullptr, &status);
  std::string name = status == 0 && readable ? readable : type.name();
  std::free(readable);
  return name;
}

// What the student's code gave that motus cannot take (an error estimate that is not a number),
// said in motus's words: its message is not "threw ...", since the student's code threw nothing.
struct Refused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "NaN", "∞", "0.1": a number in a message, as the grader writes one.
inline std::string number(double x) {
  if (std::isnan(x)) return "NaN";
  if (std::isinf(x)) return x > 0 ? "∞" : "−∞";
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

// Runs the student's code: 0 when it returned, 1 (and the message) when it threw. Out of memory,
// the message itself may not fit: then a fixed one, which needs no allocation (a bad_alloc out of
// this noexcept function ended the process: "terminate called after throwing std::bad_alloc").
template <class Work>
int guarded(Work&& work) noexcept {
  auto say = [](auto&& make) noexcept {
    try {
      last_error() = make();
    } catch (...) {
      last_error().clear();  // (error() then gives the fixed message)
    }
  };
  try {
    work();
    return 0;
  } catch (const std::bad_alloc&) {
    say([] { return std::string("ran out of memory (std::bad_alloc)"); });
  } catch (const Refused& e) {
    say([&] { return std::string(e.what()); });
  } catch (const std::exception& e) {
    say([&] { return "threw " + type_name(typeid(e)) + ": " + e.what(); });
  } catch (...) {
    say([] { return std::string("threw something that is not a std::exception"); });
  }
  return 1;
}

inline Eigen::Map<Vector> view(double* data, int n) { return {data, n}; }
inline Eigen::Map<const Vector> view(const double* data, int n) { return {data, n}; }

}  // namespace detail

class Plugin {
public:
  Plugin(const char* name, const char* description) : name_(name), description_(description) {}

  // y ← one step of h on y' = f(t, y).
  void first_order(const char* name, int order, const char* description, FirstOrderStep step) {
    auto& slot = slots_.emplace_back();
    slot.first_order = step;
    add({name, description, order, motus::kExternalFirstOrder, &slot, &first_order_step, nullptr, nullptr, nullptr,
         nullptr, &detail::error});
  }
  // (x, v) ← one step of h on point masses.
  void mechanical(const char* name, int order, const char* description, MechanicalStep step) {
    auto& slot = slots_.emplace_back();
    slot.mechanical = step;
    add({name, description, order, motus::kExternalMechanical, &slot, nullptr, nullptr, &mechanical_step, nullptr,
         nullptr, &detail::error});
  }
  // Velocityless Verlet: x_{−1} from the start, then (x_n, x_{n−1}) → (x_{n+1}, x_n).
  void position_verlet(const char* name, int order, const char* description, VerletStart start, VerletStep step) {
    auto& slot = slots_.emplace_back();
    slot.verlet_start = start;
    slot.verlet_step = step;
    add({name, description, order, motus::kExternalPositionVerlet, &slot, nullptr, nullptr, nullptr, &verlet_start,
         &verlet_step, &detail::error});
  }
  // Adaptive steps (by step doubling, or any step that estimates its own error): `step` returns
  // the new state and its error estimate, `next` the step to try next from error_ratio =
  // max_i |error_i| / tolerance_i (accepted when ≤ 1; tolerance_i = atol + rtol·max(|y_i|,
  // |y_new_i|)). An error or a new state that is NaN rejects the step and stops the run, as it
  // does motus's own adaptive integrators.
  void adaptive(const char* name, int order, const char* description, StepWithError step, NextStepSize next) {
    auto& slot = slots_.emplace_back();
    slot.step_with_error = step;
    slot.next_step = next;
    add({name, description, order, motus::kExternalAdaptive, &slot, nullptr, &adaptive_step, nullptr, nullptr,
         nullptr, &detail::error});
  }
  // The impulses and times of impact of ball–ball and ball–wall contacts.
  void collisions(CollisionFunctions functions) {
    collision_functions_ = functions;
    collisions_ = {&collision_functions_, &collide_balls, &bounce_off_wall, &balls_impact, &plane_impact,
                   &detail::error};
    entry_.collisions = &collisions_;
  }
  // The projection of sticks, pins and walls after each Verlet step.
  void constraints(SatisfyConstraints satisfy) {
    satisfy_ = satisfy;
    constraints_ = {this, &project, &detail::error};
    entry_.constraints = &constraints_;
  }

  const motus::PluginEntry* entry() {
    entry_.abi_version = motus::kPluginAbiVersion;
    entry_.name = name_;
    entry_.description = description_;
    entry_.integrator_count = static_cast<int>(integrators_.size());
    entry_.integrators = integrators_.data();
    return &entry_;
  }

private:
  struct Slot {
    FirstOrderStep first_order = nullptr;
    MechanicalStep mechanical = nullptr;
    VerletStart verlet_start = nullptr;
    VerletStep verlet_step = nullptr;
    StepWithError step_with_error = nullptr;
    NextStepSize next_step = nullptr;
  };
  static const Slot& slot(void* self) { return *static_cast<const Slot*>(self); }

  void add(motus::ExternalIntegrator integrator) { integrators_.push_back(integrator); }

  static int first_order_step(void* self, const motus::ExternalFirstOrder* f, double t, double h, double* y) {
    return detail::guarded([&] { slot(self).first_order(FirstOrderSystem(*f), t, h, detail::view(y, f->size)); });
  }
  static int adaptive_step(void* self, const motus::ExternalFirstOrder* f, double t, double* h, double* y,
                           double atol, double rtol, int* accepted) {
    return detail::guarded([&] {
      const auto y0 = detail::view(y, f->size);
      Vector error = Vector::Zero(f->size);
      const Vector y1 = slot(self).step_with_error(FirstOrderSystem(*f), t, *h, y0, error);
      if (y1.size() != f->size || error.size() != f->size)
        throw std::length_error("returned " + std::to_string(y1.size()) + " numbers and an error of " +
                                std::to_string(error.size()) + " for a state of " + std::to_string(f->size));
      double ratio = 0;
      for (int i = 0; i < f->size; ++i) {
        const double part = std::abs(error[i]) / (atol + rtol * std::fmax(std::abs(y0[i]), std::abs(y1[i])));
        // A NaN is no error of 0 (std::fmax(0, NaN) is 0: such a step was kept as exact). motus's own
        // adaptive integrators reject a step whose error is NaN — theirs is NaN too when the new state
        // is — and their controller proposes no step after it (h · NaN), which stops the run: so here,
        // whatever `next` makes of a NaN.
        if (std::isnan(part) || std::isnan(y1[i])) {
          *accepted = 0;
          std::string at(1, '[');  // "[i] = " (built by appending: GCC 12 warns, wrongly, of "[" + a string)
          at += std::to_string(i);
          at += "] = ";
          const std::string what =
              std::isnan(error[i]) ? "the error estimate your step set is not a number: error" + at + "NaN"
              : std::isnan(y1[i])  ? "the state your step gave is not a number: y" + at + "NaN (with an error estimate of " +
                                        detail::number(error[i]) + ")"
                                   : "the error estimate your step set is infinite, and so is the state: error" + at +
                                        detail::number(error[i]) + ", y" + at +
                                        detail::number(std::isinf(y1[i]) ? y1[i] : y0[i]);
          throw detail::Refused(what + " (at t = " + detail::number(t) + " with h = " + detail::number(*h) +
                                "). Such a step is rejected, as motus's own adaptive integrators reject one, and no "
                                "next step size follows from it: the run stops here");
        }
        ratio = std::fmax(ratio, part);
      }
      *accepted = ratio <= 1;
      *h = slot(self).next_step(*h, ratio);
      if (*accepted) detail::view(y, f->size) = y1;
    });
  }
  static int mechanical_step(void* self, const motus::ExternalMechanical* s, double t, double h, double* x,
                             double* v) {
    return detail::guarded([&] {
      slot(self).mechanical(MechanicalSystem(*s), t, h, detail::view(x, s->size), detail::view(v, s->size));
    });
  }
  static int verlet_start(void* self, const motus::ExternalMechanical* s, double t, double h, const double* x,
                          const double* v, double* x_previous) {
    return detail::guarded([&] {
      const Vector previous =
          slot(self).verlet_start(MechanicalSystem(*s, v), t, h, detail::view(x, s->size), detail::view(v, s->size));
      if (previous.size() != s->size)
        throw std::length_error("returned " + std::to_string(previous.size()) + " numbers for " +
                                std::to_string(s->size) + " coordinates");
      detail::view(x_previous, s->size) = previous;
    });
  }
  static int verlet_step(void* self, const motus::ExternalMechanical* s, double t, double h, double* x,
                         double* x_previous, const double* v) {
    return detail::guarded([&] {
      slot(self).verlet_step(MechanicalSystem(*s, v), t, h, detail::view(x, s->size), detail::view(x_previous, s->size));
    });
  }

  static const CollisionFunctions& collision(void* self) { return *static_cast<const CollisionFunctions*>(self); }
  static int collide_balls(void* self, int d, double* v_a, double* v_b, double m_a, double m_b, const double* n,
                           double e) {
    return detail::guarded(
        [&] { collision(self).collide_balls(m_a, detail::view(v_a, d), m_b, detail::view(v_b, d), detail::view(n, d), e); });
  }
  static int bounce_off_wall(void* self, int d, double* v, const double* n, double e) {
    return detail::guarded([&] { collision(self).bounce_off_wall(detail::view(v, d), detail::view(n, d), e); });
  }
  static int balls_impact(void* self, int d, const double* p_a, const double* v_a, double r_a, const double* p_b,
                          const double* v_b, double r_b, double* t) {
    return detail::guarded([&] {
      *t = collision(self).time_of_impact(detail::view(p_a, d), detail::view(v_a, d), r_a, detail::view(p_b, d),
                                          detail::view(v_b, d), r_b);
    });
  }
  static int plane_impact(void* self, int d, const double* p, const double* v, double r, const double* n,
                          double offset, double* t) {
    return detail::guarded([&] {
      *t = collision(self).time_of_impact_with_plane(detail::view(p, d), detail::view(v, d), r, detail::view(n, d),
                                                     offset);
    });
  }

  // The constraints of a run, made once (the engine keeps its set at one address for the run).
  static int project(void* self, const motus::ExternalConstraintSet* set, double* x) {
    auto& plugin = *static_cast<Plugin*>(self);
    return detail::guarded([&] {
      if (plugin.constraint_run_ != set->id) {
        plugin.constraint_run_ = set->id;
        const int d = set->dimensions;
        Constraints c;
        for (int i = 0; i < set->stick_count; ++i) c.sticks.push_back({set->sticks[i].a, set->sticks[i].b, set->sticks[i].length});
        for (int i = 0; i < set->pin_count; ++i)
          c.pins.push_back({set->pins[i].body, detail::view(set->pins[i].position, d)});
        for (int i = 0; i < set->wall_count; ++i)
          c.walls.push_back({detail::view(set->walls[i].normal, d), set->walls[i].offset});
        c.iterations = set->iterations;
        plugin.constraint_values_ = std::move(c);
      }
      Bodies bodies{set->dimensions, set->bodies, detail::view(x, set->dimensions * set->bodies),
                    detail::view(set->inverse_mass, set->bodies), detail::view(set->radius, set->bodies)};
      plugin.satisfy_(bodies, plugin.constraint_values_);
    });
  }

  const char* name_;
  const char* description_;
  std::deque<Slot> slots_;  // stable addresses: each integrator's self points at its slot
  std::vector<motus::ExternalIntegrator> integrators_;
  CollisionFunctions collision_functions_{};
  motus::ExternalCollisionRules collisions_{};
  SatisfyConstraints satisfy_ = nullptr;
  motus::ExternalConstraintRules constraints_{};
  long constraint_run_ = 0;  // the ExternalConstraintSet::id constraint_values_ were made for
  Constraints constraint_values_;
  motus::PluginEntry entry_{};
};

}  // namespace student

// Defines the plug-in's entry point; the body, with `plugin` in scope, says what it brings.
#define MOTUS_PLUGIN(NAME, DESCRIPTION)                                                   \
  static void motus_plugin_contents(student::Plugin& plugin);                             \
  extern "C" __attribute__((visibility("default"))) const motus::PluginEntry* motus_plugin() { \
    static student::Plugin plugin(NAME, DESCRIPTION);                                     \
    static const motus::PluginEntry* entry = [] {                                         \
      motus_plugin_contents(plugin);                                                      \
      return plugin.entry();                                                              \
    }();                                                                                  \
    return entry;                                                                         \
  }                                                                                       \
  static void motus_plugin_contents(student::Plugin& plugin)
