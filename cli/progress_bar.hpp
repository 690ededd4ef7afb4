#pragma once
// A progress bar on standard error for long runs: it appears only on a terminal (never when
// output is piped or in CI) and only once a run has taken about two seconds, so short runs
// print nothing extra. It fits the terminal's width (no wrapping, nothing left behind when it
// is erased), names the phase it is in (simulating, drawing, encoding the video), and gives the
// time to go from the rate measured in that phase alone.
//   MOTUS_PROGRESS=always  draw it from the start, also when standard error is not a terminal
//   COLUMNS=N              the width to fit (else the terminal's, else 80)
#include <chrono>
#include <string>

namespace motus {

class ProgressBar {
public:
  // Progress runs from `start` to `end` (times, or step counts).
  // The clock is read every `check_every` updates (a power of two).
  ProgressBar(double start, double end, std::string label, unsigned check_every = 256);
  ~ProgressBar();
  // Cheap enough to call every step: it looks at the clock at most every `check_every` calls,
  // more often when they come slowly. (It is also where a long loop stops for Ctrl-C, at any
  // call: see interrupt.hpp.)
  void update(double now);
  // A new phase of the work ("drawing"), running from start to end: its rate is measured anew.
  void phase(const std::string& name, double start, double end);
  // No time to go is shown: for work whose steps cost unlike amounts (bench precision's levels,
  // each halving the step, cost twice the one before: an estimate from the rate so far says
  // seconds where minutes are left).
  void without_estimate() { estimate_ = false; }
  // Shows `what` (a phase without steps, such as ffmpeg encoding) until the next update.
  void note(const std::string& what);
  void finish();

  // The line a bar of this width shows (for tests): never longer than `width` columns.
  static std::string line(const std::string& label, const std::string& phase, double fraction, double elapsed,
                          double remaining, int width);

private:
  void draw(double fraction);
  int width() const;

  double start_, end_;
  std::string label_, phase_;
  bool enabled_;
  bool always_;
  bool shown_ = false;
  unsigned calls_ = 0;
  unsigned check_mask_, most_mask_;  // the clock is read every check_mask_ + 1 calls (at most most_mask_ + 1)
  std::chrono::steady_clock::time_point began_, last_draw_, last_check_, phase_began_;
  double phase_fraction_ = 0;  // where the current phase started, for its rate
  double fraction_ = 0;
  // When (seconds into the phase) the progress last moved, and to where: the rate is measured up to
  // then, so that work that moves in whole steps (the tests of a grading, the submissions of a
  // batch) counts down between them instead of growing.
  double moved_at_ = 0, moved_to_ = -1;
  bool estimate_ = true;
};

}  // namespace motus
