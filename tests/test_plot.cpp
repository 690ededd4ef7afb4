// The figures' script (plot/motus/plot/figure.cpp) as gnuplot reads it: every line of a figure
// drawn in a style of its own, so a work-precision diagram's twenty methods and peers can be
// told apart by their looks, and not only by the order of the legend. Also the programs the plots
// need as motus finds and starts them (process/), and the progress bar of a compare.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <regex>
#include <set>
#include <string>

#include "cli_harness.hpp"
#include "motus/plot/figure.hpp"
#include "accessibility.hpp"

namespace {

using motus_test::read_file;
using motus_test::TempDir;

TEST(Figures, EveryLineOfAFigureHasItsOwnStyleUpTo32) {
  TempDir folder;
  motus::plot::Figure f;
  f.stem = "many";
  f.title = "32 lines";
  for (int k = 0; k < 32; ++k) {
    motus::plot::Series s;
    s.name = "line " + std::to_string(k);
    s.x = {0, 1};
    s.y = {double(k), double(k + 1)};
    s.dashed = k % 5 == 0;  // some are peers, drawn dashed
    f.series.push_back(s);
  }
  (void)motus::plot::draw({f}, folder.path().string());  // gnuplot or not, the script is written
  const std::string script = read_file(folder / "figures.gp");
  // Each series' style: what stands between "with lines lw 1.8" and its title.
  const std::regex one(
      R"(with lines lw 1\.8((?: dt \d)?) lc rgb '(#[0-9a-f]{6})'((?: dt (?:\d|\([0-9,]+\)))?) title 'line (\d+)')");
  std::set<std::string> styles;
  std::set<int> seen;
  const std::string png_part = script.substr(0, script.find("set terminal svg"));
  for (auto it = std::sregex_iterator(png_part.begin(), png_part.end(), one); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    styles.insert(m[1].str() + m[2].str() + m[3].str());
    seen.insert(std::stoi(m[4].str()));
    if (std::stoi(m[4].str()) % 5 == 0) {
      EXPECT_FALSE(m[3].str().empty() && m[1].str().empty()) << m[0] << ": a peer is dashed";
    }
    // Found by an accessibility audit: on a stress page symplectic Euler's line lay exactly under
    // its x-first form's, both solid, and could not be seen. Every line after the first has gaps
    // (its own dash pattern, or a peer's dashes), so a line under it shows through.
    if (std::stoi(m[4].str()) > 0) {
      EXPECT_FALSE(m[3].str().empty() && m[1].str().empty()) << m[0] << ": has gaps";
    }
  }
  EXPECT_EQ(seen.size(), 32u) << script;
  EXPECT_EQ(styles.size(), 32u) << "two lines share a colour and a dash pattern:\n" << script;
}

// Found by an accessibility audit: four of the lines' colours had less than 3:1 against the white
// background (WCAG 1.4.11), the orange, green, teal and yellow (2.96, 2.92, 2.80, 1.98). Every
// colour a figure of 16 lines is drawn in, read from the script written, now has 3:1 at least.
TEST(Figures, EveryLineColourHasAContrastOfThreeOnWhite) {
  TempDir folder;
  motus::plot::Figure f;
  f.stem = "palette";
  f.title = "16 lines";
  for (int k = 0; k < 16; ++k) {
    motus::plot::Series s;
    s.name = "line " + std::to_string(k);
    s.x = {0, 1};
    s.y = {double(k), double(k + 1)};
    f.series.push_back(s);
  }
  (void)motus::plot::draw({f}, folder.path().string());
  const std::string script = read_file(folder / "figures.gp");
  const std::regex colour(R"(lc rgb '(#[0-9a-f]{6})'(?: dt \S+)? title 'line \d+')");
  std::set<std::string> colours;
  for (auto it = std::sregex_iterator(script.begin(), script.end(), colour); it != std::sregex_iterator(); ++it)
    colours.insert((*it)[1].str());
  EXPECT_EQ(colours.size(), 16u) << script;
  for (const auto& c : colours) EXPECT_GE(motus_test::contrast_ratio(c, "#ffffff"), 3.0) << c;
}

// Found by an audit of the pictures: bench precision's note (what the markers and dashes mean)
// ran 1,100 px wide in a 1,100 px picture, cut off at both edges. A note longer than the picture
// is broken into lines that fit (about 6.75 px a character of its 9-point font), between its
// clauses, and says all of itself.
TEST(Figures, ALongNoteIsBrokenIntoLinesThatFitThePicture) {
  TempDir folder;
  motus::plot::Figure f;
  f.stem = "note";
  f.title = "a long note";
  f.width = 900;
  std::string note;
  for (int k = 0; k < 8; ++k) note += (k ? "; " : "") + std::string("clause ") + std::to_string(k) + " says what a reader needs";
  f.note = note;
  motus::plot::Series s;
  s.name = "line";
  s.x = {0, 1};
  s.y = {0, 1};
  f.series.push_back(s);
  (void)motus::plot::draw({f}, folder.path().string());
  const std::string script = read_file(folder / "figures.gp");
  const std::regex label(R"(set label 1\d '([^']*)' at screen 0\.5)");
  std::string said;
  int lines = 0;
  for (auto it = std::sregex_iterator(script.begin(), script.end(), label); it != std::sregex_iterator(); ++it, ++lines) {
    const std::string line = (*it)[1].str();
    EXPECT_LE(static_cast<double>(line.size()) * 6.75, f.width - 40.0) << line;
    said += (said.empty() ? "" : " ") + line;
  }
  EXPECT_GE(lines, 2) << script;
  EXPECT_EQ(said, note) << script;
}

// Found by an audit of the pictures: on a symlog axis ±threshold is log10(2) of a decade from 0,
// and over many decades its label printed over 0's ("0" on "1e-16": the runs' common start read
// as 1e-16). A tic closer to 0 than a label's height is left out; one farther away stays.
std::string symlog_tics(double threshold, double y_low, double y_high) {
  TempDir folder;
  motus::plot::Figure f;
  f.stem = "symlog";
  f.title = "symlog";
  f.y_scale = motus::plot::Scale::symlog;
  f.symlog_threshold = threshold;
  motus::plot::Series s;
  s.name = "line";
  s.x = {0, 1, 2};
  s.y = {y_low, 0, y_high};
  f.series.push_back(s);
  (void)motus::plot::draw({f}, folder.path().string());
  const std::string script = read_file(folder / "figures.gp");
  const size_t at = script.find("set ytics (");
  return at == std::string::npos ? "" : script.substr(at, script.find('\n', at) - at);
}

TEST(Figures, SymlogTicsCloserToZeroThanALabelAreLeftOut) {
  // Six decades each side in a 480 px figure: ±1e-07 would be ~7 px from 0.
  const std::string many = symlog_tics(1e-7, -0.1, 0.1);
  EXPECT_NE(many.find("'0' 0,"), std::string::npos) << many;
  EXPECT_NE(many.find("'1e-01' 0.1"), std::string::npos) << many;
  EXPECT_EQ(many.find("1e-07'"), std::string::npos) << many;
  // One decade each side: ±1e-07 is a third of the half axis from 0, and stays.
  const std::string few = symlog_tics(1e-7, -1e-6, 1e-6);
  EXPECT_NE(few.find("'1e-07' 1e-07"), std::string::npos) << few;
  EXPECT_NE(few.find("'-1e-07' -1e-07"), std::string::npos) << few;
}

// Found by an audit of the pictures: on `motus stress ball_gas` a line that failed from 1000 radii
// per step said "no value from x = 1000" on an axis of radii per step, in a legend entry wider than
// the picture, cut off at its right edge. The entry says where in the axis's words, and the
// picture is as wide as its widest entry (about 7.5 px a character of the legend's font).
TEST(Figures, ALineThatStopsSaysWhereInTheAxissWordsAndItsEntryFits) {
  TempDir folder;
  motus::plot::Figure f;
  f.stem = "gaps";
  f.title = "gaps";
  f.x_label = "radii per step";
  f.x_scale = f.y_scale = motus::plot::Scale::log;
  f.gap_from = "no value from", f.gap_means = "failed: see the table";
  motus::plot::Series s;
  s.name = "symplectic-euler: deepest overlap / contact distance, a name long enough to need a wider picture";
  s.x = {1, 10, 100, 1000};
  s.y = {1e-3, 1e-2, 1e-1, NAN};
  f.series.push_back(s);
  (void)motus::plot::draw({f}, folder.path().string());
  const std::string script = read_file(folder / "figures.gp");
  const std::string entry = s.name + ": no value from radii per step = 1000 (failed: see the table)";
  EXPECT_NE(script.find("title '" + entry + "'"), std::string::npos) << script;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(script, m, std::regex(R"(set terminal pngcairo size (\d+),)"))) << script;
  EXPECT_GE(std::stod(m[1].str()), 7.5 * static_cast<double>(entry.size()) + 70) << script;
  // A time axis keeps its "t = … s".
  f.x_label = "t [s]";
  f.x_scale = motus::plot::Scale::linear;
  (void)motus::plot::draw({f}, folder.path().string());
  EXPECT_NE(read_file(folder / "figures.gp").find("no value from t = 1000 s (failed"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------------
// The programs the plots need, as motus starts them (process/), and the progress bar of a compare.

namespace fs = std::filesystem;
using motus_test::kMotus;
using motus_test::run_motus;
using motus_test::run_program;
using motus_test::write_file;

// $NAME set to `value` in this process for a scope, then put back as it was (gnuplot, started by
// motus::plot::draw, inherits this process's environment).
class EnvironmentFor {
public:
  EnvironmentFor(std::string name, const std::string& value) : name_(std::move(name)) {
    if (const char* old = std::getenv(name_.c_str())) old_ = old;
    ::setenv(name_.c_str(), value.c_str(), 1);
  }
  ~EnvironmentFor() {
    if (old_) ::setenv(name_.c_str(), old_->c_str(), 1);
    else ::unsetenv(name_.c_str());
  }
  EnvironmentFor(const EnvironmentFor&) = delete;
  EnvironmentFor& operator=(const EnvironmentFor&) = delete;

private:
  std::string name_;
  std::optional<std::string> old_;
};

// Found by an audit of the programs motus starts: a user's ~/.gnuplot (`set decimalsign ","`) was
// read before figures.gp, and the tick labels of every plot read "0,5". gnuplot is started with -d
// (--default-settings), which reads neither the user's nor the system's init file.
// A pictures audit: the stress page's limits could not be read off its plot (every blow-up in the one
// decade 1 to 10, no tick there), and its stiffness plot drew every blown-up run on the frame's top edge.
// A figure's x marks are dashed grey lines from the bottom of the plot to its top (with their words when
// they have any), taken away before the next figure; y_to ends the y axis above the data.
TEST(Figures, MarksAndTheEndOfTheYAxisAreAFiguresOwn) {
  TempDir folder;
  motus::plot::Figure marked, plain;
  marked.stem = "marked", plain.stem = "plain";
  for (motus::plot::Figure* f : {&marked, &plain}) {
    f->title = f->stem;
    f->y_scale = motus::plot::Scale::log;
    f->series.push_back({"line", {1, 2, 3}, {1, 10, 1e6}});
  }
  marked.x_marks = {{2, ""}, {2.5, "theory"}};
  marked.y_to = 1e7;
  (void)motus::plot::draw({marked, plain}, folder.path().string());
  const std::string script = read_file(folder / "figures.gp");
  const size_t second = script.find("set output 'marked.svg'");
  ASSERT_NE(second, std::string::npos) << script;
  const std::string first = script.substr(0, second);
  EXPECT_NE(first.find("set arrow 20 from 2, graph 0 to 2, graph 1 nohead"), std::string::npos) << script;
  EXPECT_NE(first.find("set arrow 21 from 2.5, graph 0 to 2.5, graph 1 nohead"), std::string::npos) << script;
  EXPECT_EQ(first.find("set label 20 "), std::string::npos) << script;  // (no words)
  EXPECT_NE(first.find("set label 21 'theory' at 2.5, graph 0.98"), std::string::npos) << script;
  EXPECT_NE(first.find("set yrange [:10000000]"), std::string::npos) << script;
  // The plain figure after it: the marks taken away before it is drawn, and its y axis its data's.
  const size_t plain_start = script.rfind("set autoscale", script.find("set output 'plain.png'"));
  const std::string plain_part = script.substr(plain_start, script.find("set output 'plain.png'") - plain_start);
  EXPECT_NE(plain_part.find("unset arrow"), std::string::npos) << plain_part;
  EXPECT_NE(plain_part.find("unset label 21"), std::string::npos) << plain_part;
  EXPECT_EQ(plain_part.find("\nset arrow"), std::string::npos) << plain_part;
  EXPECT_EQ(plain_part.find("\nset yrange"), std::string::npos) << plain_part;
}

TEST(Figures, AUsersGnuplotInitFileDoesNotChangeThePlots) {
  if (motus::plot::gnuplot_program().empty()) GTEST_SKIP() << "no gnuplot on PATH";
  TempDir dir;
  fs::create_directories(dir / "home");
  fs::create_directories(dir / "figures");
  write_file(dir / "home/.gnuplot", "set decimalsign \",\"\n");
  const EnvironmentFor home("HOME", (dir / "home").string());
  motus::plot::Figure f;
  f.stem = "decimals";
  f.title = "tick labels";
  motus::plot::Series s;
  s.name = "halves";
  s.x = {0, 1, 2, 3};
  s.y = {0, 0.5, 1.5, 2.5};  // (tics every 0.5: labels with decimals)
  f.series.push_back(s);
  ASSERT_EQ(motus::plot::draw({f}, (dir / "figures").string()), "");
  const std::string svg = read_file(dir / "figures/decimals.svg");
  const std::regex label(R"(<text>\s*-?\d+([.,])\d+\s*</text>)");
  int points = 0, commas = 0;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label); it != std::sregex_iterator(); ++it)
    ((*it)[1].str() == "." ? points : commas) += 1;
  EXPECT_GT(points, 0) << svg;
  EXPECT_EQ(commas, 0) << "the labels took ~/.gnuplot's decimal sign";
}

// Found by an audit: with a relative entry in PATH (PATH=relbin:/usr/bin:/bin) gnuplot was found as
// "relbin/gnuplot" and started in the report's folder, where there is no such file: "plots failed",
// with an empty figures.log. A program found on PATH is an absolute path, made from the folder
// motus was started in.
TEST(Figures, GnuplotFoundThroughARelativePathEntryDrawsThePlots) {
  const std::string gnuplot = motus::plot::gnuplot_program();
  if (gnuplot.empty()) GTEST_SKIP() << "no gnuplot on PATH";
  TempDir dir;
  fs::create_directories(dir / "relbin");
  fs::create_symlink(fs::absolute(gnuplot), dir / "relbin/gnuplot");
  const auto r = run_program(dir, "/usr/bin/env",
                             {"-C", dir.path().string(), "PATH=relbin:/usr/bin:/bin", kMotus, "compare", "head_on", "--out",
                              "c1", "--repeats", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("plots"), std::string::npos) << r.err;
  const std::string svg = read_file(dir / "c1/energy.svg");
  EXPECT_NE(svg.find("</svg>"), std::string::npos) << "c1/energy.svg was not drawn";
}

// A gnuplot that cannot be started at all (here a file that is no program) is said to be so: the
// message pointed at the report's figures.log, which gnuplot, never started, had left empty.
TEST(Figures, AGnuplotThatCannotBeStartedIsSaidSo) {
  TempDir dir;
  fs::create_directories(dir / "bad");
  write_file(dir / "bad/gnuplot", "not a program\n");
  fs::permissions(dir / "bad/gnuplot", fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                           fs::perms::others_read | fs::perms::others_exec);
  const auto r = run_program(dir, "/usr/bin/env",
                             {"PATH=" + (dir / "bad").string() + ":/usr/bin:/bin", kMotus, "compare", "head_on", "--out",
                              (dir / "c1").string(), "--repeats", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("plots failed: gnuplot (" + (dir / "bad/gnuplot").string() + ") could not be started ("),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("figures.log"), std::string::npos) << r.err;
}

// Found by an audit of long runs in logs: MOTUS_PROGRESS=always redrew the bar at every reading of
// the clock, about 120 times a second (242 redraws in 2 s of a log), where docs/cli.md says at most
// ten a second. Counted against the wall time of the same run.
TEST(Progress, WithProgressAlwaysTheBarIsRedrawnAtMostTenTimesASecond) {
  TempDir dir;
  const auto began = std::chrono::steady_clock::now();
  const auto r = run_motus(dir, {"compare", "ball_gas", "--out", (dir / "report").string(), "--repeats", "1"},
                           {"MOTUS_PROGRESS=always", "COLUMNS=80"});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  ASSERT_EQ(r.status, 0) << r.err;
  // Each redraw writes two \r (the line and spaces to the end of the one before, then the line
  // again); the erasing at the end two more.
  const double redraws = static_cast<double>(std::count(r.err.begin(), r.err.end(), '\r')) / 2;
  EXPECT_GE(redraws, 5) << "the bar was not drawn: " << r.err;
  // Ten a second, and the few drawn at once: the first, a phase without steps as it starts
  // ("writing the report"), the erasing.
  EXPECT_LE(redraws, 10 * wall + 4) << redraws << " redraws in " << wall << " s";
}

// MOTUS_PROGRESS=every, for tests that read each value a short run's bar took (drawn within a few
// milliseconds of each other), draws at every reading of the clock: more than ten a second.
TEST(Progress, WithProgressEveryTheBarIsDrawnAtEveryReadingOfTheClock) {
  TempDir dir;
  const auto began = std::chrono::steady_clock::now();
  const auto r = run_motus(dir, {"run", "head_on", "--duration", "2000", "--repeats", "1"},
                           {"MOTUS_PROGRESS=every", "COLUMNS=80"});
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  ASSERT_EQ(r.status, 0) << r.err;
  const double redraws = static_cast<double>(std::count(r.err.begin(), r.err.end(), '\r')) / 2;
  EXPECT_GT(redraws, 10 * wall + 4) << redraws << " redraws in " << wall << " s";
}

// Found by an audit: `motus compare ball_gas --render` sat at "drawing 100%" for 9.5 s while the
// video and the contact sheet were made. That phase is named as it starts.
TEST(Progress, CompareRenderSaysSoWhileItMakesTheVideo) {
  TempDir dir;
  const auto r = run_motus(dir, {"compare", "head_on", "--render", "--size", "160x120", "--out", (dir / "report").string(),
                                 "--repeats", "1"},
                           {"MOTUS_PROGRESS=always", "COLUMNS=120"});
  ASSERT_EQ(r.status, 0) << r.err;
  const size_t drawn = r.err.rfind("compare head_on, drawing [##############################] 100%");
  const size_t video = r.err.find("compare head_on, making the contact sheet and the video");
  ASSERT_NE(video, std::string::npos) << r.err;
  EXPECT_TRUE(drawn == std::string::npos || drawn < video) << r.err;
  EXPECT_LT(video, r.err.find("compare head_on, writing the report")) << r.err;
}

}  // namespace
