// An order test: the student's integrator's global order, measured by halving its step against the
// scene's exact solution.
#include "motus/grade/checks/check_kinds.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <ranges>

#include "motus/exact/exact_solution.hpp"
#include "motus/grade/checks/check_support.hpp"
#include "motus/scene_error.hpp"
#include "motus/simulation.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

namespace {

// The part of a state a check compares: x (positions), v, or all of it.
Vector part(const Vector& y, const std::string& which) {
  const Eigen::Index half = y.size() / 2;
  if (which == "x") return y.head(half);
  if (which == "v") return y.tail(half);
  return y;
}

std::string read_part(JsonFields& f, const SceneDescription& scene) {
  const std::string which = f.string("compare", scene.mechanical ? "x" : "state");
  if (which != "x" && which != "v" && which != "state") f.fail("compare", "must be \"x\", \"v\" or \"state\"");
  if (which != "state" && !scene.mechanical) f.fail("compare", "\"x\" and \"v\" are for scenes of bodies");
  return which;
}

class OrderCheck final : public Check {
public:
  OrderCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts, std::string hint)
      : scene_(load_check_scene(f, test, source)), hint_(std::move(hint)) {
    if (!has_exact_solution(scene_.description))
      throw SceneError(f.path_of("scene"), "an order check needs a scene with an exact solution or reference states");
    const RunsStudent integrator = student_integrator(f, parts, "an order test");
    check_runs_scene(f, integrator, scene_.description, parts);
    integrator_ = integrator.name;
    dt_ = f.positive("dt", scene_.description.dt);
    duration_ = f.positive("duration", scene_.description.duration);
    // (At least two: the order is read at the two finest pairs of step sizes, and one halving
    // makes one pair — where a step whose error does not shrink at all can show any order.)
    halvings_ = static_cast<int>(f.integer("halvings", 4));
    if (halvings_ < 2 || halvings_ > 16)
      f.fail("halvings", fmt::format("must be from 2 to 16 (got {}): the order is read at the two finest pairs of "
                                     "successive step sizes, and {} halving{} make{} {}",
                                     halvings_, halvings_, halvings_ == 1 ? "" : "s", halvings_ == 1 ? "s" : "",
                                     halvings_ == 1 ? "one pair" : halvings_ < 1 ? "none" : "too many runs"));
    which_ = read_part(f, scene_.description);
    expected_ = f.positive("expect");
    tolerance_ = f.positive("tolerance", 0.2);
    // What it usually means when the error does not shrink with h at all (an order below 0.5):
    // then the step itself is wrong, and the hint about what lowers the order would mislead.
    hint_no_order_ = f.string("hint_no_order", "");
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    std::vector<double> hs, errors;
    for (int k = 0; k <= halvings_; ++k) {
      const double h = dt_ / std::ldexp(1.0, k);
      RunRequest r;
      r.integrator = integrator_;
      r.dt = h;
      r.steps = fixed_step_count(duration_, h);
      r.every = r.steps;
      const RunOutput out = grade::run(probe, scene_, r, deadline);
      const auto exact = exact_state(scene_.description, out.t.back());
      if (!exact) throw std::runtime_error("no exact state at t = " + num(out.t.back()));
      const Vector diff = part(out.y.back(), which_) - part(*exact, which_);
      const double error = diff.allFinite() ? diff.cwiseAbs().maxCoeff() : INFINITY;
      hs.push_back(h);
      errors.push_back(error);
    }
    // The orders of the finest kReadPairs pairs of successive step sizes whose errors both stand
    // above rounding (1e-12), each within the tolerance; none when a run blew up (an order from
    // the coarser pairs would pass code that fails at small steps). One pair is not enough: a
    // wrong step whose error does not shrink at all (velocityless Verlet with h for h²) has
    // errors of order 1 whose ratios are chance, and one of them may look like the right order.
    const auto blew_up = std::find_if(errors.begin(), errors.end(), [](double e) { return !std::isfinite(e); });
    struct Pair {
      size_t fine;  // the pair of hs[fine - 1] and hs[fine]
      double order;
    };
    std::vector<Pair> read;  // from the coarser to the finer
    for (size_t k = errors.size() - 1; blew_up == errors.end() && k >= 1 && read.size() < kReadPairs; --k)
      if (errors[k] > kRounding && errors[k - 1] > kRounding)
        read.insert(read.begin(), {k, std::log2(errors[k - 1] / errors[k])});
    std::vector<std::string> orders;
    for (const auto& p : read)
      orders.push_back(fmt::format("{} (h = {} to {})", num(p.order), num(hs[p.fine - 1]), num(hs[p.fine])));
    std::string what;
    if (blew_up != errors.end())
      what = fmt::format("no order: the error at h = {} is not finite (the run blew up, or gave NaN)",
                         num(hs[static_cast<size_t>(blew_up - errors.begin())]));
    else if (read.empty() && std::ranges::all_of(errors, [](double e) { return e <= kRounding; }))
      what = "no order: every error is at rounding's level (below 1e-12)";
    else if (read.empty())
      what = "no order: no two successive step sizes have errors both above rounding's level (1e-12)";
    else if (read.size() == 1)
      what = "global order " + orders.front();
    else
      what = fmt::format("global orders {} and {} between successive halvings",
                         fmt::join(orders.begin(), orders.end() - 1, ", "), orders.back());
    std::vector<std::string> table;
    for (size_t k = 0; k < hs.size(); ++k) table.push_back(fmt::format("h = {}: error {}", num(hs[k]), num(errors[k])));
    const std::string measured = fmt::format("{}, from the errors at the end ({})", what, fmt::join(table, "; "));
    const std::string expected =
        fmt::format("order {} ± {}{}", num(expected_), num(tolerance_),
                    read.size() > 1 ? fmt::format(" at each of the {} finest halvings", read.size()) : "");
    const bool ok = !read.empty() && std::ranges::all_of(read, [&](const Pair& p) {
      return std::abs(p.order - expected_) <= tolerance_;
    });
    if (ok) return pass(measured);
    // (An order below 0: the error grows.)
    const auto lowest = std::ranges::min_element(read, {}, &Pair::order);
    const bool no_order = lowest != read.end() && lowest->order < 0.5 && !hint_no_order_.empty();
    return fail(measured, expected,
                no_order ? fmt::format("the error does not shrink as h does (order {} from h = {} to {}): {}", num(lowest->order),
                                       num(hs[lowest->fine - 1]), num(hs[lowest->fine]), hint_no_order_)
                         : hint_);
  }

private:
  // Pairs read: two, not all (of halvings = 3's three, the reference RK4 on the Lorenz system
  // gives 5.24 at the coarsest, before its error settles into h⁴; 3.86 and 3.87 at the two finest).
  static constexpr size_t kReadPairs = 2;
  static constexpr double kRounding = 1e-12;  // an error at or below this is rounding's
  CheckScene scene_;
  std::string integrator_, which_;
  double dt_, duration_, expected_, tolerance_;
  int halvings_;
  std::string hint_, hint_no_order_;
};

}  // namespace

std::unique_ptr<Check> detail::make_order_check(JsonFields& f, const json& test, const SceneSource& source,
                                                const StudentParts& parts, const std::string& hint) {
  return std::make_unique<OrderCheck>(f, test, source, parts, hint);
}

}  // namespace motus::grade
