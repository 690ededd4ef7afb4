#pragma once
// A progress bar on standard error for long runs: it appears only on a terminal (never when
// output is piped or in CI) and only once a run has taken about two seconds, so short runs
// print nothing extra. It fits the terminal's width (no wrapping, nothing left behind when it
// is erased), names the phase it is in (simulating, drawing, encoding the video), and gives the
// time to go from the rate measured in that phase alone. It is redrawn at most ten times a
// second, also in a log (MOTUS_PROGRESS=always redrew it at every reading of the clock: 120 lines
// a second of a CI log), except its first line and a note, which are drawn at once.
//   MOTUS_PROGRESS=always  draw it from the start, also when standard error is not a terminal
//   MOTUS_PROGRESS=every   as always, and at every reading of the clock: for tests that read each
//                          value the bar took (a short run's, drawn within a few milliseconds)
//   COLUMNS=N              the width to fit (else the terminal's, else 80)
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

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
  void without_estimate() {
    stop_ticking();
    estimate_ = false;
  }
  // Names the step under way in this phase (the test a grading runs), shown after the phase's
  // name and before its bar until the next step or phase. Drawn by the next update or refresh
  // that draws.
  void step(const std::string& name);
  // Shows `what` (a phase without steps, such as ffmpeg encoding) until the next update: its
  // name and the seconds so far, no bar. Drawn at once, and redrawn by a thread of its own while
  // it lasts, since no update may come meanwhile (the seconds stood still for the 26 s of a video's
  // ffmpeg); so one a phase, not one a step. Until the next call of any other member the caller
  // must leave the bar alone (every member stops that thread first). The phase it follows keeps its
  // range: an update after it shows that phase's fraction again (a note had made it 100 %).
  void note(const std::string& what);
  // Redraws what the bar shows, when a redraw is due: the seconds go on during a wait with
  // nothing to count (a compiler's run). Unlike update, never a place to stop for Ctrl-C: it
  // may be called from a callback that is asked whether to stop.
  void refresh();
  void finish();

  // The line a bar of this width shows (for tests): never longer than `width` columns.
  static std::string line(const std::string& label, const std::string& phase, double fraction, double elapsed,
                          double remaining, int width);

private:
  using Clock = std::chrono::steady_clock;
  // Whether a line is to be drawn now: enabled, after the first two seconds (from the start with
  // MOTUS_PROGRESS=always), and a tenth of a second after the last line (except the first).
  bool due(Clock::time_point clock) const;
  // The note's redraws (note()): a thread that draws when due until stop_ticking, which every other
  // member calls first, so that only one thread draws at a time.
  void start_ticking();
  void stop_ticking() {
    if (ticker_.joinable()) stop_ticker();
  }
  void stop_ticker();
  void draw(Clock::time_point clock);
  int width() const;

  double start_, end_;
  double now_;  // the last update's value
  std::string label_, phase_;
  std::string step_;  // the step under way (step()), or ""
  std::string note_;  // the note shown until the next update (note()), or ""
  bool enabled_;
  bool always_;
  bool every_;
  bool shown_ = false;
  unsigned calls_ = 0;
  unsigned check_mask_, most_mask_;  // the clock is read every check_mask_ + 1 calls (at most most_mask_ + 1)
  Clock::time_point began_, last_draw_, last_check_, phase_began_;
  // When (seconds into the phase) the progress last moved, and to where: the rate is measured up to
  // then, so that work that moves in whole steps (the tests of a grading, the submissions of a
  // batch) counts down between them instead of growing.
  double moved_at_ = 0, moved_to_ = -1;
  bool estimate_ = true;
  std::thread ticker_;
  std::mutex ticker_mutex_;
  std::condition_variable ticker_wake_;
  bool ticker_stop_ = false;
};

}  // namespace motus
