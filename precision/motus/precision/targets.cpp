#include "motus/precision/targets.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace motus::precision {

std::optional<AtTarget> at_target(const Curve& curve, double target) {
  // The points that were measured, cheapest first (the sweep's order).
  std::vector<const Point*> points;
  for (const Point& p : curve.points)
    // (Evaluations may be 0: a step with no force evaluates nothing, symplectic Euler among collisions.)
    if (p.failed.empty() && p.seconds > 0 && std::isfinite(p.seconds) && p.evaluations >= 0) points.push_back(&p);
  // An error is not monotone along a sweep: an adaptive method's in its tolerance (dop853 on Kepler
  // reaches 3e-7 at rtol 1e-6 and 6e-7 at 1e-8), a peer's among collisions in its step (Bullet's
  // head_on is exact at one dt and 0.3 m off at the next three), and every method's error rises
  // again at its most expensive points, where rounding takes over. So the curve reaches the target
  // at its first point below it whose next point is below it too (or that is the last): a lone
  // point below between two above is a lucky dip, not a method that gets there; a rise at the
  // expensive end does not undo the cheaper points that got there.
  size_t first = points.size();
  for (size_t i = 0; i < points.size() && first == points.size(); ++i)
    if (points[i]->error <= target && (i + 1 == points.size() || points[i + 1]->error <= target)) first = i;
  if (first == points.size()) return std::nullopt;
  const Point& p = *points[first];
  // Nothing to interpolate from — the cheapest point is already below the target, the one before it
  // is not finite (a blow-up), or p's error is exactly 0 — and the time is at most p's.
  if (first == 0 || p.error <= 0 || !std::isfinite(points[first - 1]->error))
    return AtTarget{p.seconds, p.median_seconds, static_cast<double>(p.evaluations), true};
  const Point& previous = *points[first - 1];
  // log t = log t0 + f (log t1 − log t0), f = (log E − log e0) / (log e1 − log e0)
  const double f = std::log(target / previous.error) / std::log(p.error / previous.error);
  auto between = [f](double a, double b) { return std::exp(std::log(a) + f * std::log(b / a)); };
  const double evaluations = previous.evaluations > 0 && p.evaluations > 0
                                 ? between(static_cast<double>(previous.evaluations), static_cast<double>(p.evaluations))
                                 : static_cast<double>(p.evaluations);
  return AtTarget{between(previous.seconds, p.seconds), between(previous.median_seconds, p.median_seconds), evaluations,
                  false};
}

std::optional<Fastest> fastest(const std::vector<Curve>& curves, const std::string& engine, double target) {
  std::optional<Fastest> best;
  for (const Curve& c : curves) {
    if (c.engine != engine) continue;
    const auto at = at_target(c, target);
    if (at && (!best || at->seconds < best->at.seconds)) best = Fastest{c.method, *at};
  }
  return best;
}

bool engine_runs(const std::vector<Curve>& curves, const std::string& engine) {
  return std::any_of(curves.begin(), curves.end(),
                     [&](const Curve& c) { return c.engine == engine && c.unsupported.empty(); });
}

std::optional<double> smallest_error(const std::vector<Curve>& curves, const std::string& engine) {
  std::optional<double> best;
  for (const Curve& c : curves) {
    if (c.engine != engine || !c.unsupported.empty()) continue;
    for (const Point& p : c.points)
      if (p.failed.empty() && std::isfinite(p.error) && (!best || p.error < *best)) best = p.error;
  }
  return best;
}

std::string not_reached_text(const std::vector<Curve>& curves, const std::string& engine, bool ascii) {
  const auto best = smallest_error(curves, engine);
  if (!best) return "not reached";
  std::string e = fmt::format("{:.2g}", *best);
  if (!ascii)
    if (const size_t minus = e.find("e-"); minus != std::string::npos) e.replace(minus + 1, 1, "−");
  return "not reached (best " + e + ")";
}

std::string ratio_text(const std::optional<Fastest>& motus, const std::optional<Fastest>& peer, bool ascii) {
  const std::string none = ascii ? "-" : "–";
  if (!motus || !peer || (motus->at.upper_bound && peer->at.upper_bound)) return none;
  // A time that is a bound (at most) makes the ratio one: at most when it is motus's, at least
  // when it is the peer's.
  const std::string bound = motus->at.upper_bound ? (ascii ? "<=" : "≤ ") : peer->at.upper_bound ? (ascii ? ">=" : "≥ ") : "";
  // (Two decimals, or two significant figures below 0.01: motus 0.81 µs against Bullet's 1,030 µs
  // is 0.00079, which two decimals showed as 0.00.)
  auto ratio = [](double r) { return fmt::format(fmt::runtime(r >= 0.01 ? "{:.2f}" : "{:.2g}"), r); };
  return fmt::format("{}{} ({})", bound, ratio(motus->at.seconds / peer->at.seconds),
                     ratio(motus->at.median_seconds / peer->at.median_seconds));
}

std::vector<double> default_targets() { return {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}; }

}  // namespace motus::precision
