#include "motus/precision/timing_rounds.hpp"

#include <algorithm>
#include <cmath>

#include "motus/precision/run_times.hpp"

namespace motus::precision {

std::vector<Curve> sweep_in_rounds(const std::vector<SweepOf>& sweeps, const Sweep& sweep) {
  Sweep round = sweep;
  round.round = 0;
  std::vector<std::vector<Curve>> untimed;
  for (const SweepOf& run : sweeps) untimed.push_back(run(round));

  // times[s][c][p]: the timed runs of point p of sweep s's curve c.
  std::vector<std::vector<std::vector<RunTimes>>> times(untimed.size());
  for (size_t s = 0; s < untimed.size(); ++s)
    for (const Curve& c : untimed[s]) times[s].emplace_back(c.points.size());
  auto has_points_to_time = [&](size_t s) {
    return std::any_of(untimed[s].begin(), untimed[s].end(), [](const Curve& c) {
      return c.unsupported.empty() &&
             std::any_of(c.points.begin(), c.points.end(), [](const Point& p) { return p.failed.empty(); });
    });
  };
  std::vector<size_t> to_time;
  for (size_t s = 0; s < sweeps.size(); ++s)
    if (has_points_to_time(s)) to_time.push_back(s);
  for (int r = 1; r <= sweep.repeats; ++r) {
    round.round = r;
    for (size_t k = 0; k < to_time.size(); ++k) {
      const size_t s = to_time[compare::taking_turns(to_time.size(), static_cast<size_t>(r - 1), k)];
      const std::vector<Curve> timed = sweeps[s](round);
      for (size_t c = 0; c < std::min(timed.size(), untimed[s].size()); ++c)
        for (size_t p = 0; p < std::min(timed[c].points.size(), untimed[s][c].points.size()); ++p)
          if (untimed[s][c].points[p].failed.empty() && timed[c].points[p].failed.empty())
            times[s][c][p].add(timed[c].points[p].seconds);
    }
  }

  std::vector<Curve> curves;
  for (size_t s = 0; s < untimed.size(); ++s)
    for (size_t c = 0; c < untimed[s].size(); ++c) {
      Curve& curve = untimed[s][c];
      if (sweep.repeats > 0)
        for (size_t p = 0; p < curve.points.size(); ++p) {
          Point& point = curve.points[p];
          if (!point.failed.empty()) continue;
          const RunTimes& t = times[s][c][p];
          // (The runs are deterministic: a point that finished untimed finishes timed. Should one not,
          // its numbers are not those of a run that was timed.)
          if (t.empty()) point.failed = "its untimed run finished, its timed runs did not";
          point.seconds = t.fastest();
          point.median_seconds = t.median();
        }
      curves.push_back(std::move(curve));
    }
  return curves;
}

}  // namespace motus::precision
