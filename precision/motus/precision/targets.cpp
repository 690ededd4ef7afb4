#include "motus/precision/targets.hpp"

#include <cmath>

namespace motus::precision {

std::optional<AtTarget> at_target(const Curve& curve, double target) {
  const Point* previous = nullptr;
  for (const Point& p : curve.points) {
    if (!p.failed.empty() || !(p.seconds > 0) || !std::isfinite(p.seconds)) continue;
    if (p.error <= target) {
      if (!previous || p.error <= 0)
        return AtTarget{p.seconds, p.median_seconds, static_cast<double>(p.evaluations), !previous};
      // log t = log t0 + f (log t1 − log t0), f = (log E − log e0) / (log e1 − log e0)
      const double f = std::log(target / previous->error) / std::log(p.error / previous->error);
      auto between = [f](double a, double b) { return std::exp(std::log(a) + f * std::log(b / a)); };
      return AtTarget{between(previous->seconds, p.seconds), between(previous->median_seconds, p.median_seconds),
                      between(static_cast<double>(previous->evaluations), static_cast<double>(p.evaluations)), false};
    }
    previous = std::isfinite(p.error) && p.evaluations > 0 ? &p : nullptr;
  }
  return std::nullopt;
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

std::vector<double> default_targets() { return {1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10}; }

}  // namespace motus::precision
