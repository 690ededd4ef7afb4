// An adaptive test: the student's adaptive integrator's error at the end, its steps changing with the
// error, and fewer evaluations than motus's fixed-step RK4 at the same error.
#include "motus/grade/checks/check_kinds.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "motus/exact/exact_solution.hpp"
#include "motus/grade/checks/check_support.hpp"
#include "motus/integrate/integrator_catalog.hpp"
#include "motus/scene_error.hpp"
#include "motus/simulation.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

namespace {

class AdaptiveCheck final : public Check {
public:
  // (Its failures say what each failed condition usually means; the test's hint is for a run that
  // stops or runs out of time, which the grader shows.)
  AdaptiveCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts)
      : scene_(load_check_scene(f, test, source)) {
    if (!has_exact_solution(scene_.description))
      throw SceneError(f.path_of("scene"), "an adaptive check needs a scene with an exact solution");
    const RunsStudent integrator = student_integrator(f, parts, "an adaptive test");
    // (A fixed-step one never changes its step: every submission failed "its step size changes".)
    if (!integrator.kind.empty() && integrator.kind != "adaptive") {
      std::vector<std::string> adaptive;
      for (const auto& i : parts.integrators)
        if (i.kind == "adaptive") adaptive.push_back(i.name);
      f.fail("integrator", fmt::format("{} takes fixed steps; an adaptive test needs an adaptive integrator of the "
                                       "student's: {}",
                                       integrator.name,
                                       adaptive.empty() ? "the plug-in brings none" : listed(adaptive, "or")));
    }
    check_runs_scene(f, integrator, scene_.description, parts);
    integrator_ = integrator.name;
    tolerance_ = f.positive("tolerance");
    first_step_ = f.positive("first_step", scene_.description.dt);
    duration_ = f.positive("duration", scene_.description.duration);
    max_error_ = f.positive("max_error");
    // motus's own adaptive method at the same tolerance, run in the same check: the student's
    // error may be at most `factor` times its error.
    if (f.has("compare_with")) {
      const auto builtin = integrator_from_name(f.string("compare_with"));
      if (!builtin || !info(*builtin).adaptive) f.fail("compare_with", "must name one of motus's adaptive integrators");
      compare_with_ = *builtin;
      factor_ = f.positive("factor", 2);
    }
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    RunRequest r;
    r.integrator = integrator_;
    r.dt = first_step_;
    r.until = scene_.description.start_time + duration_;
    r.every = 1;  // every step's time: the step sizes the controller chose
    r.atol = r.rtol = tolerance_;
    const RunOutput out = grade::run(probe, scene_, r, deadline);
    const double error = error_at_end(out.y.back(), out.t.back());
    // The steps it took, but the last (shortened to land on the end): an adaptive run's change
    // with the error. A controller that keeps h as it is can still beat fixed-step RK4 with the
    // doubling's extrapolation alone, and must not pass as adaptive.
    double smallest = INFINITY, largest = 0;
    for (size_t i = 1; i + 1 < out.t.size(); ++i) {
      smallest = std::min(smallest, out.t[i] - out.t[i - 1]);
      largest = std::max(largest, out.t[i] - out.t[i - 1]);
    }
    const bool adapts = largest >= 2 * smallest;
    // motus's own fixed-step RK4, halving h until it is as accurate — or until it has spent
    // more evaluations than the student's run, which settles the comparison.
    long rk4_evaluations = -1;
    bool rk4_needs_more = false;
    for (int k = 0; k < 30 && std::isfinite(error); ++k) {
      Simulation sim(scene_.description, Integrator::Rk4);
      const double h = first_step_ / std::ldexp(1.0, k);
      if (fixed_step_count(r.until - sim.time(), h) * 4 > std::max(out.evaluations, 1L) * 2) {
        rk4_needs_more = true;
        break;
      }
      sim.advance(r.until, h, Tolerance{});
      if (error_at_end(sim.state(), sim.time()) <= error) {
        rk4_evaluations = sim.evaluations();
        break;
      }
    }
    double peer_error = NAN;
    std::string peer;
    if (compare_with_) {
      Simulation sim(scene_.description, *compare_with_);
      sim.advance(r.until, first_step_, Tolerance{tolerance_, tolerance_});
      peer_error = error_at_end(sim.state(), sim.time());
      peer = fmt::format("; motus's {} at the same tolerance: error {}", info(*compare_with_).name, num(peer_error));
    }
    const std::string measured = fmt::format(
        "at tolerance {}: error {} at t = {} after {} steps ({} rejected; h from {} to {}) and {} evaluations; motus's "
        "fixed-step rk4 needs {} evaluations for that error",
        num(tolerance_), num(error), num(out.t.back()), out.steps, out.rejected, num(smallest), num(largest),
        out.evaluations, rk4_needs_more ? "more than " + std::to_string(out.evaluations) : std::to_string(rk4_evaluations)) +
        peer + (out.evaluations == 0 ? " (your step never called f.derivative: it cannot have moved the state)" : "");
    const bool lands = std::abs(out.t.back() - r.until) <= 1e-9 * std::max(1.0, std::abs(r.until));
    const bool fewer = rk4_needs_more || (rk4_evaluations > 0 && out.evaluations < rk4_evaluations);
    const bool accurate = error <= max_error_;
    const bool as_good = !compare_with_ || error <= factor_ * peer_error;
    const bool ok = lands && accurate && fewer && as_good && adapts;
    if (ok) return pass(measured);
    // Each condition that failed, and what it usually means: the test's own hint would name every
    // cause at once. Steps 5 times the one before, with none rejected, are the mark of an error
    // estimate that is exactly 0 (next_step_size(h, 0) is 5 h).
    bool grew_fivefold = out.rejected == 0 && out.t.size() > 3;
    for (size_t i = 2; grew_fivefold && i + 1 < out.t.size(); ++i)
      grew_fivefold = std::abs((out.t[i] - out.t[i - 1]) / (out.t[i - 1] - out.t[i - 2]) - 5) < 1e-6;
    std::vector<std::string> causes;
    if (!lands)
      causes.push_back(fmt::format("The run stopped at t = {}, not at its end, t = {}.", num(out.t.back()), num(r.until)));
    if (!adapts)
      causes.push_back(fmt::format("The step size never changed (h from {} to {}): next_step_size keeps h; it must be "
                                   "h · 0.9 · ratio^(-1/5), between h/5 and 5 h.",
                                   num(smallest), num(largest)));
    if (grew_fivefold)
      causes.push_back("Every step was 5 times the one before and none was rejected: the error was exactly 0 at every "
                       "step, so rk4_doubling_step never sets error (it must be (y_half - y_full)/15).");
    else if (!accurate || !as_good)
      causes.push_back(fmt::format("The error at the end is larger than {}: steps whose error is above the tolerance were "
                                   "accepted, or the step is less accurate than it should be. rk4_doubling_step's error "
                                   "must be (y_half - y_full)/15, and it returns y_half + error (fifth order; y_half alone "
                                   "is fourth).",
                                   // (the bound it missed: within the test's own, it can still miss motus's by the factor)
                                   !accurate ? num(max_error_)
                                             : fmt::format("{} × motus's {} ({})", num(factor_), info(*compare_with_).name,
                                                           num(factor_ * peer_error))));
    if (!fewer && !grew_fivefold)
      causes.push_back("It needed more evaluations than fixed-step RK4 at the same error: steps smaller than they need "
                       "be. The controller's exponent is -1/5 (a larger error, a smaller step: written -1.0 / 5, since "
                       "-1 / 5 is 0 in integer arithmetic), and the factor 0.9.");
    causes.push_back("Step doubling calls your rk4_step: a wrong rk4_step fails this test too (see the rk4 tests).");
    return fail(measured,
                fmt::format("the run lands on t = {}, its error is at most {}{}, it needs fewer evaluations "
                            "than fixed-step RK4 at the same error, and its step size changes with the error (the "
                            "largest step at least twice the smallest)",
                            num(r.until), num(max_error_),
                            compare_with_ ? fmt::format(" and at most {} × motus's {}", num(factor_), info(*compare_with_).name)
                                          : ""),
                fmt::format("{}", fmt::join(causes, " ")));
  }

private:
  double error_at_end(const Vector& y, double t) const {
    const auto exact = exact_state(scene_.description, t);
    if (!exact) return INFINITY;
    const Vector diff = y - *exact;
    return diff.allFinite() ? diff.cwiseAbs().maxCoeff() : INFINITY;
  }
  CheckScene scene_;
  std::string integrator_;
  double tolerance_, first_step_, duration_, max_error_;
  std::optional<Integrator> compare_with_;
  double factor_ = 2;
};

}  // namespace

std::unique_ptr<Check> detail::make_adaptive_check(JsonFields& f, const json& test, const SceneSource& source,
                                                   const StudentParts& parts) {
  return std::make_unique<AdaptiveCheck>(f, test, source, parts);
}

}  // namespace motus::grade
