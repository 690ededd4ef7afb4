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
  // An adaptive method's error is not monotone in its tolerance (dop853 on Kepler reaches 3e-7 at
  // rtol 1e-6 and 6e-7 at 1e-8): read the curve where it goes below the target for good, after its
  // last point above it, never at a lucky dip.
  long last_above = -1;
  for (size_t i = 0; i < points.size(); ++i)
    if (!(points[i]->error <= target)) last_above = static_cast<long>(i);
  if (points.empty() || last_above == static_cast<long>(points.size()) - 1) return std::nullopt;
  const Point& p = *points[static_cast<size_t>(last_above + 1)];
  if (last_above < 0 || p.error <= 0 || !std::isfinite(points[static_cast<size_t>(last_above)]->error))
    return AtTarget{p.seconds, p.median_seconds, static_cast<double>(p.evaluations), last_above < 0};
  const Point& previous = *points[static_cast<size_t>(last_above)];
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

std::string ratio_text(const std::optional<Fastest>& motus, const std::optional<Fastest>& peer, bool ascii) {
  const std::string none = ascii ? "-" : "–";
  if (!motus || !peer || (motus->at.upper_bound && peer->at.upper_bound)) return none;
  // A time that is a bound (at most) makes the ratio one: at most when it is motus's, at least
  // when it is the peer's.
  const std::string bound = motus->at.upper_bound ? (ascii ? "<=" : "≤ ") : peer->at.upper_bound ? (ascii ? ">=" : "≥ ") : "";
  return fmt::format("{}{:.2f} ({:.2f})", bound, motus->at.seconds / peer->at.seconds,
                     motus->at.median_seconds / peer->at.median_seconds);
}

std::vector<double> default_targets() { return {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}; }

}  // namespace motus::precision
