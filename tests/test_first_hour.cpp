// What a new user meets in the first hour (README.md, docs/cli.md): `motus run spring` shows
// the course's table (tests/reference/integrators.md: x = 20, 20, 10, −10, −35, −55; v = 0, −10,
// −20, −25, −20, −2.5; a = −10, −10, −5, 5, 17.5, 27.5), `--trajectory -` writes the CSV to
// standard output, a changed scene says so, times read as times, and the progress bar never
// wraps a terminal of 40, 80 or 160 columns.
#include <gtest/gtest.h>

#include <sstream>

#include "cli_harness.hpp"

namespace {

using namespace motus_test;

// The rows of a table printed with columns t, x, v, a.
std::vector<std::vector<double>> table_rows(const std::string& out) {
  std::vector<std::vector<double>> rows;
  std::stringstream lines(out);
  std::string line;
  bool in_table = false;
  while (std::getline(lines, line)) {
    std::stringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (w == std::vector<std::string>{"t", "x", "v", "a"}) {
      in_table = true;
      continue;
    }
    if (in_table && w.size() == 4) {
      rows.push_back({std::stod(w[0]), std::stod(w[1]), std::stod(w[2]), std::stod(w[3])});
    } else if (in_table) {
      break;
    }
  }
  return rows;
}

TEST(FirstHour, RunSpringShowsTheCourseTable) {
  TempDir dir;
  const auto r = run_motus(dir, {"run", "spring"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = table_rows(r.out);
  const std::vector<std::vector<double>> expected = {
      {0, 20, 0, -10}, {1, 20, -10, -10}, {2, 10, -20, -5}, {3, -10, -25, 5}, {4, -35, -20, 17.5}, {5, -55, -2.5, 27.5}};
  EXPECT_EQ(rows, expected) << r.out;
  EXPECT_NE(r.out.find("final state       x = (-55)   v = (-2.5)"), std::string::npos) << r.out;
}

TEST(FirstHour, TrajectoryDashIsTheCsvOnStandardOutput) {
  TempDir dir;
  const auto r = run_motus(dir, {"run", "spring", "--trajectory", "-"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("t,x0,vx0,kinetic,potential,total\n0,20,0,", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\n5,-55,-2.5,"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("kinetic energy"), std::string::npos);  // the summary, on standard error
  EXPECT_FALSE(fs::exists(dir / "-"));
}

TEST(FirstHour, AChangedSceneSaysItsDescriptionIsTheFiles) {
  TempDir dir;
  const auto r = run_motus(dir, {"run", "spring", "--set", "bodies[0].mass=2"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("(the description is the file's; this run changed bodies[0].mass=2)"), std::string::npos) << r.out;
  // A scene with no description has none to disown: the change alone (it spoke of a description not shown).
  const auto bare = run_motus(dir, {"run", "spring", "--set", "description=", "--set", "bodies[0].mass=2"});
  ASSERT_EQ(bare.status, 0) << bare.err;
  EXPECT_NE(bare.out.find("             (this run changed description=, bodies[0].mass=2)"), std::string::npos) << bare.out;
  EXPECT_EQ(bare.out.find("the description is the file's"), std::string::npos) << bare.out;
  // An empty name is the default, the file's name (it printed a blank title).
  const auto unnamed = run_motus(dir, {"run", "spring", "--set", "name="});
  ASSERT_EQ(unnamed.status, 0) << unnamed.err;
  EXPECT_EQ(unnamed.out.rfind("scene        spring  (", 0), 0u) << unnamed.out;
}

TEST(FirstHour, TimesReadAsTimes) {
  TempDir dir;
  const auto r = run_motus(dir, {"run", "world2", "--steps", "3"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("(years)"), std::string::npos) << r.out;
  const auto wall = r.out.find("wall time    ");
  ASSERT_NE(wall, std::string::npos);
  const std::string line = r.out.substr(wall, r.out.find('\n', wall) - wall);
  // Three significant digits in the largest unit reached: never "5279703.0 ns", never "927.0 ns"
  // (a clock of whole nanoseconds over 3 steps made a tenth of one look measured), never "1e+03 ns".
  EXPECT_EQ(line.find(".0 "), std::string::npos) << line;
  EXPECT_EQ(line.find("e+"), std::string::npos) << line;
  EXPECT_TRUE(line.find(" ns") != std::string::npos || line.find(" µs") != std::string::npos ||
              line.find(" ms") != std::string::npos || line.find(" s") != std::string::npos)
      << line;
}

// Every redraw of the bar, at 40, 80 and 160 columns: never longer than the width (in
// characters; the bar is drawn with ASCII and the phase names), so a terminal never wraps it.
TEST(FirstHour, TheProgressBarFitsTheTerminal) {
  for (int width : {40, 80, 160}) {
    TempDir dir;
    const auto r = run_motus(dir, {"render", "newtons_cradle", "--out", (dir / "frames").string(), "--size", "64x48",
                                   "--fps", "10", "--duration", "1"},
                             {"MOTUS_PROGRESS=every", "COLUMNS=" + std::to_string(width)});
    ASSERT_EQ(r.status, 0) << r.err;
    size_t lines = 0;
    std::string piece;
    for (char c : r.err + "\n") {
      if (c == '\r' || c == '\n') {
        size_t chars = 0;
        for (unsigned char b : piece) chars += (b & 0xC0) != 0x80;
        EXPECT_LT(chars, static_cast<size_t>(width)) << "at width " << width << ": \"" << piece << "\"";
        lines += !piece.empty();
        piece.clear();
      } else {
        piece += c;
      }
    }
    EXPECT_GT(lines, 10u) << "at width " << width << ": the bar was not drawn";
    EXPECT_NE(r.err.find("drawing"), std::string::npos) << "the drawing phase is shown";
  }
}

// Slow steps (a 200 × 200 cloth's take tens of milliseconds) show the bar from the first ones: the
// clock was read every 256th step at first, so the first bar between 0.3 s steps came after 77 s
// (found by an audit of big inputs). 40 steps here: none was drawn before the last. (MOTUS_PROGRESS=
// every draws at every read of the clock; "always" drew at most every 0.1 s, and so needed steps
// of 25 ms or more to show five bars by half-way: a faster machine would have failed it.)
TEST(FirstHour, TheProgressBarComesFromTheFirstSlowSteps) {
  TempDir dir;
  const auto r = run_motus(dir, {"run", "cloth", "--set", "cloth.rows=200", "--set", "cloth.columns=200", "--steps", "40",
                                 "--repeats", "1"},
                           {"MOTUS_PROGRESS=every", "COLUMNS=80"});
  ASSERT_EQ(r.status, 0) << r.err;
  long bars = 0;
  for (const char* percent : {"  0%", "  2%", "  5%", "  8%", " 10%", " 12%", " 15%", " 18%", " 20%", " 22%", " 25%",
                              " 28%", " 30%", " 32%", " 35%", " 38%", " 40%", " 42%", " 45%", " 48%", " 50%"})
    bars += r.err.find(percent) != std::string::npos;
  EXPECT_GE(bars, 5) << r.err;
}

}  // namespace
