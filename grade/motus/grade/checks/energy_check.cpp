// An energy test: the energy of a long run of the student's integrator, bounded or growing by a
// given factor a step, as motus measures it.
#include "motus/grade/checks/check_kinds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "motus/grade/checks/check_support.hpp"
#include "motus/scene_error.hpp"
#include "motus/systems/mechanical_system.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

namespace {

class EnergyCheck final : public Check {
public:
  EnergyCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts, std::string hint)
      : scene_(load_check_scene(f, test, source)), hint_(std::move(hint)) {
    if (!scene_.description.mechanical) throw SceneError(f.path_of("scene"), "an energy check needs a scene of bodies");
    const RunsStudent integrator = student_integrator(f, parts, "an energy test");
    check_runs_scene(f, integrator, scene_.description, parts);
    integrator_ = integrator.name;
    dt_ = f.positive("dt", scene_.description.dt);
    steps_ = f.integer("steps");
    if (steps_ < 1 || steps_ > 10'000'000) f.fail("steps", "must be from 1 to 10,000,000");
    auto e = f.object("expect");
    if (e.has("bounded")) bounded_ = e.positive("bounded");
    if (e.has("growth_per_step")) growth_ = e.positive("growth_per_step");
    tolerance_ = e.positive("tolerance", 1e-9);
    e.reject_unknown();
    if (std::isnan(bounded_) == std::isnan(growth_)) f.fail("expect", "needs exactly one of bounded, growth_per_step");
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    RunRequest r;
    r.integrator = integrator_;
    r.dt = dt_;
    r.steps = steps_;
    r.every = std::max(1L, steps_ / 200);
    const RunOutput out = grade::run(probe, scene_, r, deadline);
    const MechanicalSystem system = measuring_system(scene_.description);
    const double e0 = energy(system, out.y.front());
    // A state that is not a number (or infinite) is said to be one, and where it was first seen: a
    // run of NaN read as one whose "state changed by at most 0 of its size" (std::max(moved, NaN) is
    // moved). The state is looked at every r.every steps, so it went wrong after the last finite one.
    for (size_t k = 0; k < out.y.size(); ++k) {
      if (out.y[k].allFinite()) continue;
      auto step_at = [&](size_t i) { return std::lround((out.t[i] - out.t.front()) / dt_); };
      const std::string became = out.y[k].hasNaN() ? "not a number (NaN)" : "infinite";
      const std::string measured =
          k == 0 ? fmt::format("the state was {} at the start", became)
                 : fmt::format("the state became {} by step {} (t = {}): it is looked at every {} of the {} steps, and was "
                               "finite at step {} (t = {})",
                               became, step_at(k), num(out.t[k]), r.every, out.steps, step_at(k - 1), num(out.t[k - 1]));
      const std::string want = !std::isnan(growth_)
                                   ? fmt::format("energy × {}^{}, from states that are numbers", num(growth_), out.steps)
                                   : "a run whose states are numbers, and whose energy stays within " + num(bounded_);
      return fail(measured, want,
                  "an operation that gives NaN — 0/0, ∞ − ∞, the square root of a negative number — or a variable used "
                  "before it is set; a state that becomes infinite first grew without bound. Print x and v in your step "
                  "to see where they first go wrong.");
    }
    if (!std::isnan(growth_)) {
      const double ratio = energy(system, out.y.back()) / e0;
      const double expected = std::pow(growth_, static_cast<double>(out.steps));
      const std::string measured = fmt::format("energy × {} after {} steps", num(ratio), out.steps);
      const std::string want = fmt::format("× {} = {}^{} (to {} relative)", num(expected), num(growth_), out.steps, num(tolerance_));
      return std::abs(ratio / expected - 1) <= tolerance_ ? pass(measured) : fail(measured, want, hint_);
    }
    // Bounded: small, and no larger in the second half of the run than in the first — for a
    // run that moves at all (a method that leaves the state alone keeps every energy).
    double moved = 0;
    for (const auto& y : out.y) moved = std::max(moved, (y - out.y.front()).norm() / std::max(out.y.front().norm(), 1e-300));
    if (!(moved > 0.01))
      return fail(fmt::format("the state changed by at most {} of its size over {} steps", num(moved), out.steps),
                  "a run that moves (and keeps its energy within " + num(bounded_) + ")", hint_);
    double first = 0, second = 0;
    for (size_t k = 0; k < out.y.size(); ++k) {
      const double error = std::abs(energy(system, out.y[k]) - e0) / std::abs(e0);
      double& half = 2 * k < out.y.size() ? first : second;
      half = std::isfinite(error) ? std::max(half, error) : INFINITY;
    }
    const std::string measured =
        fmt::format("largest |E − E₀|/|E₀| {} in the first half of {} steps, {} in the second", num(first), out.steps, num(second));
    const bool ok = first <= bounded_ && second <= bounded_ && second <= 1.5 * first + 1e-12;
    return ok ? pass(measured)
              : fail(measured, fmt::format("at most {}, and not growing (the second half ≤ 1.5 × the first)", num(bounded_)),
                     hint_);
  }

private:
  CheckScene scene_;
  std::string integrator_;
  double dt_;
  long steps_;
  double bounded_ = NAN, growth_ = NAN, tolerance_ = 1e-9;
  std::string hint_;
};

}  // namespace

std::unique_ptr<Check> detail::make_energy_check(JsonFields& f, const json& test, const SceneSource& source,
                                                 const StudentParts& parts, const std::string& hint) {
  return std::make_unique<EnergyCheck>(f, test, source, parts, hint);
}

}  // namespace motus::grade
