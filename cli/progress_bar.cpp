#include "progress_bar.hpp"

#include "interrupt.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace motus {

ProgressBar::ProgressBar(double start, double end, std::string label, unsigned check_every)
    : start_(start), end_(end), label_(std::move(label)), enabled_(isatty(STDERR_FILENO) != 0),
      check_mask_(check_every - 1), began_(std::chrono::steady_clock::now()), last_draw_(began_) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(double now) {
  if ((++calls_ & check_mask_) != 0) return;
  cli::stop_if_interrupted();  // every long loop reports its progress here: a safe point to stop at
  if (!enabled_) return;
  const auto clock = std::chrono::steady_clock::now();
  const double elapsed = std::chrono::duration<double>(clock - began_).count();
  if (elapsed < 2.0) return;
  if (shown_ && std::chrono::duration<double>(clock - last_draw_).count() < 0.1) return;
  last_draw_ = clock;
  const double fraction = end_ > start_ ? std::clamp((now - start_) / (end_ - start_), 0.0, 1.0) : 1.0;
  draw(fraction, elapsed);
}

void ProgressBar::draw(double fraction, double elapsed) {
  constexpr int width = 30;
  const int filled = static_cast<int>(fraction * width);
  std::string bar(static_cast<size_t>(filled), '#');
  bar.resize(width, '.');
  const double remaining = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
  std::fprintf(stderr, "\r%s [%s] %5.1f%%  %.0f s, about %.0f s to go ", label_.c_str(), bar.c_str(),
               100 * fraction, elapsed, remaining);
  std::fflush(stderr);
  shown_ = true;
}

void ProgressBar::finish() {
  if (!shown_) return;
  std::fprintf(stderr, "\r%*s\r", 80, "");  // clear the line for the summary
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace motus
