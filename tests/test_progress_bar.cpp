// The progress bar of long runs (cli/progress_bar.hpp), on its own: its seconds, and a note's redraws.
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "progress_bar.hpp"

namespace {

// Standard error, into a file, while it lives; text() reads what was written.
class CapturedStderr {
public:
  CapturedStderr() : file_(std::tmpfile()) {
    std::fflush(stderr);
    saved_ = dup(STDERR_FILENO);
    dup2(fileno(file_), STDERR_FILENO);
  }
  ~CapturedStderr() {
    restore();
    std::fclose(file_);
  }
  std::string text() {
    restore();
    std::string all;
    std::rewind(file_);
    for (int c; (c = std::fgetc(file_)) != EOF;) all += static_cast<char>(c);
    return all;
  }

private:
  void restore() {
    if (saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, STDERR_FILENO);
    close(saved_);
    saved_ = -1;
  }
  std::FILE* file_;
  int saved_ = -1;
};

}  // namespace

// 119.6 s was "1 min 60 s" (bench precision --levels 20 showed it): the minutes and the seconds were
// rounded apart. Whole seconds first: 2 min 00 s; 59.6 s is 1 min 00 s; 3,599.6 s an hour.
TEST(ProgressBar, ItsSecondsRoundToWholeSecondsBeforeTheMinutes) {
  const auto shown = [](double elapsed) { return motus::ProgressBar::line("run", "", -1, elapsed, NAN, 200); };
  EXPECT_EQ(shown(119.6), "run  2 min 00 s");
  EXPECT_EQ(shown(59.6), "run  1 min 00 s");
  EXPECT_EQ(shown(59.4), "run  59 s");
  EXPECT_EQ(shown(61.2), "run  1 min 01 s");
  EXPECT_EQ(shown(3599.6), "run  1.0 h");
  // And the time to go the same way.
  EXPECT_EQ(motus::ProgressBar::line("run", "", 0.5, 119.6, 119.6, 80).substr(0, 3), "run");
  EXPECT_NE(motus::ProgressBar::line("run", "", 0.5, 119.6, 119.6, 200).find("~2 min 00 s to go"), std::string::npos);
}

// A note (a phase without steps: ffmpeg encoding a video) was drawn once and its seconds then stood
// still for the 26 s the video took (an audit of long runs): it is redrawn while it lasts, its seconds
// going on, and not after the bar is finished.
TEST(ProgressBar, ANotesSecondsGoOnWhileItLasts) {
  setenv("MOTUS_PROGRESS", "always", 1);
  setenv("COLUMNS", "80", 1);
  std::string written;
  double lasted = 0;  // the note's seconds, as long as it lasted here (a loaded machine's sleep overruns)
  {
    CapturedStderr captured;
    {
      const auto began = std::chrono::steady_clock::now();
      motus::ProgressBar bar(0, 1, "video");
      bar.note("encoding");
      std::this_thread::sleep_for(std::chrono::milliseconds(2300));
      lasted = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
      bar.finish();
      std::this_thread::sleep_for(std::chrono::milliseconds(600));  // (nothing more once finished)
    }
    written = captured.text();
  }
  unsetenv("MOTUS_PROGRESS");
  ASSERT_FALSE(written.empty()) << "nothing was drawn";
  // Each drawing is "\r<line><spaces>\r<line>": the lines that name the note, and the seconds of each.
  int drawings = 0;
  long last_seconds = -1;
  for (size_t at = written.find("video, encoding  "); at != std::string::npos;
       at = written.find("video, encoding  ", at + 1)) {
    ++drawings;
    last_seconds = std::strtol(written.c_str() + at + std::string("video, encoding  ").size(), nullptr, 10);
  }
  EXPECT_GE(drawings, 4) << written;         // (twice a drawing: at once, then at 0.25 s steps over 2.3 s)
  EXPECT_GE(last_seconds, 2) << written;     // the seconds went on, to the 2.3 s the note lasted
  EXPECT_LE(last_seconds, std::lround(lasted) + 1) << written;
  EXPECT_EQ(written.substr(written.rfind('\r', written.size() - 2)).find("encoding"), std::string::npos)
      << "the bar was drawn again after finish()";
}
