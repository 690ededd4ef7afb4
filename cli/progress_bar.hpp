#pragma once
// A progress bar on standard error for long runs: it appears only on a terminal
// (never when output is piped or in CI) and only once a run has taken about two
// seconds, so short runs print nothing extra.
#include <chrono>
#include <string>

namespace motus {

class ProgressBar {
public:
  // Progress runs from `start` to `end` (times, or step counts).
  // The clock is read every `check_every` updates (a power of two).
  ProgressBar(double start, double end, std::string label, unsigned check_every = 256);
  ~ProgressBar();
  // Cheap enough to call every step: it looks at the clock every `check_every` calls.
  void update(double now);
  void finish();

private:
  void draw(double fraction, double elapsed_seconds);

  double start_, end_;
  std::string label_;
  bool enabled_;
  bool shown_ = false;
  unsigned calls_ = 0;
  unsigned check_mask_;
  std::chrono::steady_clock::time_point began_, last_draw_;
};

}  // namespace motus
