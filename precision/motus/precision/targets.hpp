#pragma once
// A curve read at a target error: the run time (and evaluations) a method needs to reach it,
// interpolated on log–log axes between the two points of its sweep that bracket the target where
// the curve first gets below it to stay for at least two points in a row (or at its last point) —
// that first point below, and the one before it, above. A curve whose cheapest point is already
// there gives that point's time as an upper bound (so does a point after a blow-up, or with an
// error of exactly 0: nothing to interpolate on log axes); one that never gets there gives nothing.
#include <optional>
#include <string>
#include <vector>

#include "motus/precision/work_precision.hpp"

namespace motus::precision {

struct AtTarget {
  double seconds = 0;         // from the points' fastest runs
  double median_seconds = 0;  // from the points' median runs
  double evaluations = 0;
  bool upper_bound = false;  // the time is at most `seconds` (see at_target)
};

std::optional<AtTarget> at_target(const Curve& curve, double target);

struct Fastest {
  std::string method;
  AtTarget at;
};

// The fastest curve at the target among those whose engine is `engine` (motus's own methods:
// "motus"; a plug-in's: its name; "odeint", "box2d", "bullet").
std::optional<Fastest> fastest(const std::vector<Curve>& curves, const std::string& engine, double target);

// Whether any of `engine`'s curves could run the scene (one that cannot has reached nothing: it is
// "cannot run this scene", not "not reached").
bool engine_runs(const std::vector<Curve>& curves, const std::string& engine);

// The smallest error any point of `engine`'s curves reached (none when no point was measured): what
// the table gives beside "not reached", since a curve that does not reach a target may stop short of
// it (its error stops falling: rounding, a first-order method) or only the sweep does (its finest
// step or tightest tolerance, 1e-13, is where it ends).
std::optional<double> smallest_error(const std::vector<Curve>& curves, const std::string& engine);

// "not reached (best 6.7e-10)", or "not reached" when no point was measured. `ascii`: "e-10", else "e−10".
std::string not_reached_text(const std::vector<Curve>& curves, const std::string& engine, bool ascii = false);

// motus's time over a peer's at a target, fastest runs (median runs): "0.52 (0.55)"; a bound where
// one side is (its cheapest point already below the target): "≤ …" when motus's is, "≥ …" when
// the peer's is; "–" when both are, or either reached nothing. `ascii`: "<=", ">=" and "-".
std::string ratio_text(const std::optional<Fastest>& motus, const std::optional<Fastest>& peer, bool ascii = false);

// Every decade from 1e-4 to 1e-10 (the targets).
std::vector<double> default_targets();

}  // namespace motus::precision
