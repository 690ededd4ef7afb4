#include "progress_bar.hpp"

#include <pthread.h>
#include <signal.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <system_error>

#include "interrupt.hpp"

namespace motus {
namespace {

// The number of terminal columns a UTF-8 string takes (one per code point: the bar uses no
// wide characters).
size_t columns(const std::string& s) {
  size_t n = 0;
  for (unsigned char c : s) n += (c & 0xC0) != 0x80;
  return n;
}

std::string seconds_text(double s) {
  char text[32];
  // Whole seconds first: 119.6 s is "2 min 00 s" (its minutes and seconds rounded apart said "1 min 60 s").
  const double whole = std::round(s);
  if (whole < 60) std::snprintf(text, sizeof text, "%.0f s", whole);
  else if (whole < 3600) std::snprintf(text, sizeof text, "%.0f min %02.0f s", std::floor(whole / 60), std::fmod(whole, 60));
  else std::snprintf(text, sizeof text, "%.1f h", s / 3600);
  return text;
}

}  // namespace

ProgressBar::ProgressBar(double start, double end, std::string label, unsigned check_every)
    : start_(start), end_(end), now_(start), label_(std::move(label)), check_mask_(0), most_mask_(check_every - 1),
      began_(Clock::now()), last_draw_(began_), last_check_(began_), phase_began_(began_) {
  const char* mode = std::getenv("MOTUS_PROGRESS");
  every_ = mode && std::string(mode) == "every";
  always_ = every_ || (mode && std::string(mode) == "always");
  enabled_ = always_ || isatty(STDERR_FILENO) != 0;
}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::start_ticking() {
  if (!enabled_ || ticker_.joinable()) return;
  ticker_stop_ = false;
  // The thread takes no signal: Ctrl-C and the alarms of interrupt.cpp stay the main thread's, whose
  // wait for ffmpeg they interrupt. (It inherits the mask it is started with.)
  sigset_t all, before;
  sigfillset(&all);
  pthread_sigmask(SIG_SETMASK, &all, &before);
  try {
    ticker_ = std::thread([this] {
      std::unique_lock lock(ticker_mutex_);
      // (A quarter of a second: the seconds shown change once a second.)
      while (!ticker_wake_.wait_for(lock, std::chrono::milliseconds(250), [this] { return ticker_stop_; })) {
        const auto clock = Clock::now();
        if (due(clock)) draw(clock);
      }
    });
  } catch (const std::system_error&) {
    // (No thread to be had: the note stays as drawn, as it did before; not a reason to fail the run.)
  }
  pthread_sigmask(SIG_SETMASK, &before, nullptr);
}

void ProgressBar::stop_ticker() {
  {
    std::lock_guard lock(ticker_mutex_);
    ticker_stop_ = true;
  }
  ticker_wake_.notify_one();
  ticker_.join();
}

int ProgressBar::width() const {
  if (const char* env = std::getenv("COLUMNS"); env && std::atoi(env) > 0) return std::atoi(env);
  winsize size{};
  if (ioctl(STDERR_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0) return size.ws_col;
  return 80;
}

void ProgressBar::phase(const std::string& name, double start, double end) {
  stop_ticking();
  phase_ = name;
  start_ = start;
  end_ = end;
  now_ = start;
  step_.clear();
  note_.clear();
  phase_began_ = Clock::now();
  moved_at_ = 0, moved_to_ = -1;
  calls_ = 0;
}

void ProgressBar::step(const std::string& name) {
  stop_ticking();
  step_ = name;
}

void ProgressBar::note(const std::string& what) {
  stop_ticking();
  note_ = what;
  // (The phase's range stays: it was set to 0…0 here, and the next update of a grading's tests
  // drew 100 % with 2 of 31 done.)
  const auto clock = Clock::now();
  if (enabled_ && (shown_ || always_ || std::chrono::duration<double>(clock - began_).count() >= 2.0)) draw(clock);
  start_ticking();
}

void ProgressBar::refresh() {
  stop_ticking();
  const auto clock = Clock::now();
  if (due(clock)) draw(clock);
}

bool ProgressBar::due(Clock::time_point clock) const {
  if (!enabled_) return false;
  if (!always_ && std::chrono::duration<double>(clock - began_).count() < 2.0) return false;
  return !shown_ || every_ || std::chrono::duration<double>(clock - last_draw_).count() >= 0.1;
}

void ProgressBar::update(double now) {
  stop_ticking();
  // Every long loop reports its progress here: a safe point to stop at, at every call (a flag's
  // read), however long a step takes.
  cli::stop_if_interrupted();
  now_ = now;
  note_.clear();  // (the phase goes on: a note lasts until the next update)
  if ((++calls_ & check_mask_) != 0) return;
  const auto clock = Clock::now();
  // The clock is read about every 10 ms: more often between slow steps (a 500 × 500 cloth's
  // take 0.4 s: a bar every 256 of them came after minutes), less often between fast ones. It
  // starts at every call and backs off (starting at every 256th, the first bar between slow steps
  // came after 77 s).
  const double since = std::chrono::duration<double>(clock - last_check_).count();
  last_check_ = clock;
  if (since > 0.02 && check_mask_ > 0) {
    check_mask_ >>= 1;
  } else if (since < 0.005 && check_mask_ < most_mask_) {
    check_mask_ = check_mask_ * 2 + 1;
  }
  if (due(clock)) draw(clock);
}

std::string ProgressBar::line(const std::string& label, const std::string& phase, double fraction, double elapsed,
                              double remaining, int width) {
  const std::string name = phase.empty() ? label : label + ", " + phase;
  std::string tail;
  if (fraction < 0) {
    tail = "  " + seconds_text(elapsed);  // a phase without steps: no bar, no estimate
  } else {
    char percent[16];
    std::snprintf(percent, sizeof percent, " %3.0f%%", 100 * fraction);
    tail = std::string(percent) + "  " + seconds_text(elapsed) +
           (std::isfinite(remaining) && remaining > 0 ? ", ~" + seconds_text(remaining) + " to go" : "");
  }
  // name [#####.....] tail — the bar takes what is left, between 10 and 30 columns; with less
  // room it goes, and then the name is cut: the line is always at most width − 1 columns.
  const int room = width - 1 - static_cast<int>(columns(name)) - static_cast<int>(columns(tail)) - 3;
  std::string out = name;
  if (fraction >= 0 && room >= 10) {
    const int bar = std::min(room, 30);
    const int filled = static_cast<int>(fraction * bar);
    out += " [" + std::string(static_cast<size_t>(filled), '#') + std::string(static_cast<size_t>(bar - filled), '.') + "]";
  }
  out += tail;
  while (static_cast<int>(columns(out)) > width - 1 && !out.empty()) {
    out.pop_back();
    while (!out.empty() && (static_cast<unsigned char>(out.back()) & 0xC0) == 0x80) out.pop_back();
  }
  return out;
}

void ProgressBar::draw(Clock::time_point clock) {
  last_draw_ = clock;
  const double elapsed = std::chrono::duration<double>(clock - began_).count();
  double fraction = -1, remaining = NAN;  // (a note: a phase without steps, no bar, no estimate)
  std::string name = note_;
  if (note_.empty()) {
    name = step_.empty() ? phase_ : phase_.empty() ? step_ : phase_ + " " + step_;
    fraction = end_ > start_ ? std::clamp((now_ - start_) / (end_ - start_), 0.0, 1.0) : 1.0;
    // The time to go from this phase's own rate (a fast first phase says nothing of a slow one).
    const double in_phase = std::chrono::duration<double>(clock - phase_began_).count();
    if (fraction != moved_to_) moved_to_ = fraction, moved_at_ = in_phase;
    // (At the last move's rate, less the time since: never past 0, then no estimate until it moves.)
    if (estimate_ && fraction > 0 && moved_at_ > 0.2)
      remaining = (1 - fraction) * moved_at_ / fraction - (in_phase - moved_at_);
  }
  const int w = width();
  const std::string text = line(label_, name, fraction, elapsed, remaining, w);
  // \r, the line, and spaces to the end of what the last one took: nothing is left behind.
  std::fprintf(stderr, "\r%s%*s\r%s", text.c_str(), std::max(0, w - 1 - static_cast<int>(columns(text))), "", text.c_str());
  std::fflush(stderr);
  shown_ = true;
}

void ProgressBar::finish() {
  stop_ticking();
  if (!shown_) return;
  std::fprintf(stderr, "\r%*s\r", width() - 1, "");  // clear the line for the summary
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace motus
