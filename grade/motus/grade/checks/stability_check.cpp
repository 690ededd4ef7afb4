// A stability test: the largest step at which the student's integrator keeps an oscillator bounded,
// found by bisection, against theory's limit.
#include "motus/grade/checks/check_kinds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "motus/grade/checks/check_support.hpp"
#include "motus/scene_error.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

namespace {

class StabilityCheck final : public Check {
public:
  StabilityCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts, std::string hint)
      : scene_(load_check_scene(f, test, source)), hint_(std::move(hint)) {
    const auto& m = scene_.description.mechanical;
    if (!m || m->dimensions != 1 || m->bodies.size() != 1)
      throw SceneError(f.path_of("scene"), "a stability check runs one body in 1-D (an oscillator)");
    const RunsStudent integrator = student_integrator(f, parts, "a stability test");
    check_runs_scene(f, integrator, scene_.description, parts);
    integrator_ = integrator.name;
    omega_ = f.positive("omega", 1);
    steps_ = f.integer("steps", 10000);
    if (steps_ < 100 || steps_ > 10'000'000) f.fail("steps", "must be from 100 to 10,000,000");
    limit_ = f.positive("expect");
    tolerance_ = f.positive("tolerance", 0.01);
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    double lo = 0.5 * limit_, hi = 1.5 * limit_;
    bool low_ok = bounded(probe, lo, deadline), high_ok = bounded(probe, hi, deadline);
    // A limit far from the expected one still gets measured: that number is what tells a student
    // which mistake it is (explicit Euler's 10,000 steps stay bounded only below ωh ≈ 0.037, a
    // scheme that never blows up has none). The bracket moves by factors of two, ten at most.
    for (int i = 0; !low_ok && i < kBracketMoves; ++i) hi = lo, lo *= 0.5, low_ok = bounded(probe, lo, deadline);
    for (int i = 0; high_ok && i < kBracketMoves; ++i) lo = hi, hi *= 2, high_ok = bounded(probe, hi, deadline);
    const std::string expected = fmt::format("largest stable step ωh = {} within {}%", num(limit_), num(100 * tolerance_));
    if (!low_ok)
      return fail(fmt::format("the run blows up at every step tried, down to ωh = {} ({} steps each)", num(lo), steps_),
                  expected, hint_);
    if (high_ok)
      return fail(fmt::format("the run stays bounded at every step tried, up to ωh = {} ({} steps each)", num(hi), steps_),
                  expected, hint_);
    for (int i = 0; i < 12; ++i) {
      const double mid = 0.5 * (lo + hi);
      (bounded(probe, mid, deadline) ? lo : hi) = mid;
    }
    const double measured = 0.5 * (lo + hi);
    const std::string text = fmt::format("largest stable step ωh = {} (bisection over {} steps each)", num(measured), steps_);
    return std::abs(measured - limit_) <= tolerance_ * limit_ ? pass(text) : fail(text, expected, hint_);
  }

private:
  static constexpr int kBracketMoves = 10;  // (from 2⁻¹⁰ to 2¹⁰ times the expected limit's bracket)

  // Whether steps_ steps of h = z/ω keep the amplitude √(x² + (v/ω)²) within 1000× its start.
  bool bounded(Probe& probe, double z, Clock::time_point deadline) const {
    RunRequest r;
    r.integrator = integrator_;
    r.dt = z / omega_;
    r.steps = steps_;
    r.every = std::max(1L, steps_ / 100);
    const RunOutput out = grade::run(probe, scene_, r, deadline);
    auto amplitude = [&](const Vector& y) { return std::hypot(y[0], y[1] / omega_); };
    const double start = amplitude(out.y.front());
    for (const auto& y : out.y)
      if (!(amplitude(y) <= 1000 * start)) return false;  // NaN and ∞ count as blown up
    return true;
  }

  CheckScene scene_;
  std::string integrator_;
  double omega_, limit_, tolerance_;
  long steps_;
  std::string hint_;
};

}  // namespace

std::unique_ptr<Check> detail::make_stability_check(JsonFields& f, const json& test, const SceneSource& source,
                                                    const StudentParts& parts, const std::string& hint) {
  return std::make_unique<StabilityCheck>(f, test, source, parts, hint);
}

}  // namespace motus::grade
