#pragma once
// The timed runs of one point. The machine is shared and noisy: the fastest run is the one least
// disturbed (the point's time, and what the targets compare), the median says how typical it was.
#include <algorithm>
#include <cmath>
#include <vector>

namespace motus::precision {

class RunTimes {
public:
  void add(double seconds) { seconds_.push_back(seconds); }
  double fastest() const {
    return seconds_.empty() ? INFINITY : *std::min_element(seconds_.begin(), seconds_.end());
  }
  double median() const {
    if (seconds_.empty()) return INFINITY;
    std::vector<double> s = seconds_;
    std::sort(s.begin(), s.end());
    const size_t n = s.size();
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
  }

private:
  std::vector<double> seconds_;
};

}  // namespace motus::precision
