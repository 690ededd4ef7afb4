#pragma once
// How a point of `motus bench precision` is timed. A run's time is CPU time, as `motus compare`
// takes it (compare/timing.hpp: time spent waiting for a core on a busy machine is not counted),
// from just before its first step to just after its last: what it builds first (motus's Simulation,
// Odeint's stepper and state, Box2D's or Bullet's world) is left out alike for every engine. The
// machine is shared and noisy: the fastest of a point's timed runs is the one least disturbed (the
// point's time, and what the targets compare), the median says how typical it was.
#include <algorithm>
#include <cmath>
#include <vector>

#include "motus/compare/timing.hpp"

namespace motus::precision {

// CPU seconds from start() to stop().
class Stopwatch {
public:
  void start() { began_ = compare::cpu_seconds(); }
  void stop() { seconds_ = compare::cpu_seconds() - began_; }
  double seconds() const { return seconds_; }

private:
  double began_ = 0, seconds_ = 0;
};

class RunTimes {
public:
  void add(double seconds) { seconds_.push_back(seconds); }
  bool empty() const { return seconds_.empty(); }
  double fastest() const {
    return seconds_.empty() ? INFINITY : *std::min_element(seconds_.begin(), seconds_.end());
  }
  double median() const { return seconds_.empty() ? INFINITY : compare::summarize(seconds_).median; }

private:
  std::vector<double> seconds_;
};

}  // namespace motus::precision
