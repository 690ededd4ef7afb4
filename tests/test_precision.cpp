// `motus bench precision` and its peers (precision/, issue 12). Every number is checked against
// theory or against motus in the same test, never against a timing:
//   - Odeint's runge_kutta4 on the same right-hand side reaches the same error as motus's rk4 at
//     the same step (the same method: the same numbers, to rounding);
//   - Box2D and Bullet on free fall at dt = 1/60 are off by symplectic Euler's error, g h t / 2
//     (v_n = v0 + g t_n exactly, x_n = x0 + v0 t_n + g t_n²/2 + g h t_n/2);
//   - the run folder holds the CSV, the diagrams and the page, the CSV every method and peer, and
//     what a peer cannot run is said, never dropped;
//   - bad peers and flags are one line and exit 2.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <unistd.h>
#include <string>

#include "accessibility.hpp"
#include "cli_harness.hpp"
#include "motus/compare/timing.hpp"
#include "motus/precision/engine_peers.hpp"
#include "motus/precision/motus_sweep.hpp"
#include "motus/precision/odeint_peer.hpp"
#include "motus/precision/targets.hpp"
#include "motus/precision/timing_rounds.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace {

using namespace motus_test;
using namespace motus;

SceneDescription shipped(const std::string& name) { return load_scene(scene(name)); }

// A short sweep, one run per point (nothing here reads a time).
precision::Sweep short_sweep(const SceneDescription& s, int levels) {
  precision::Sweep sweep;
  sweep.end = s.start_time + s.duration;
  sweep.dt = s.dt;
  sweep.levels = levels;
  sweep.per_decade = 1;
  sweep.repeats = 0;
  return sweep;
}

const precision::Curve& curve_named(const std::vector<precision::Curve>& curves, const std::string& method) {
  for (const auto& c : curves)
    if (c.method == method) return c;
  ADD_FAILURE() << "no curve " << method;
  return curves.front();
}

// ---------------------------------------------------------------------------------------------------------
// Odeint on the same right-hand side.

// `rounding`: how far two runs that differ only by the rounding of their stages may end apart.
void expect_odeint_rk4_is_motus_rk4(const std::string& name, double rounding = 1e-12) {
  const SceneDescription s = shipped(name);
  const precision::Sweep sweep = short_sweep(s, 3);
  const precision::Curve motus = precision::sweep_motus(s, Integrator::Rk4, sweep);
  const auto odeint = precision::sweep_odeint(s, sweep);
  const precision::Curve& rk4 = curve_named(odeint, "odeint:runge_kutta4");
  ASSERT_EQ(rk4.points.size(), motus.points.size());
  for (size_t i = 0; i < rk4.points.size(); ++i) {
    const auto &a = motus.points[i], &b = rk4.points[i];
    EXPECT_EQ(a.h, b.h);
    EXPECT_EQ(a.steps, b.steps);
    EXPECT_EQ(a.evaluations, b.evaluations) << "4 a step, both";
    EXPECT_DOUBLE_EQ(a.t_end, b.t_end);
    // The error itself is 1e-3 … 1e-9 here; the two differ only by the rounding of the stages.
    EXPECT_NEAR(a.error, b.error, rounding + 1e-9 * a.error) << name << " at h = " << a.h;
    EXPECT_GT(a.error, 0);
  }
  // Order 4: halving h divides the error by about 16.
  EXPECT_NEAR(std::log2(rk4.points[1].error / rk4.points[2].error), 4.0, 0.3) << name;
}

TEST(OdeintPeer, Rk4AtAFixedStepIsMotusRk4OnKepler) { expect_odeint_rk4_is_motus_rk4("kepler"); }
TEST(OdeintPeer, Rk4AtAFixedStepIsMotusRk4OnTheOscillator) { expect_odeint_rk4_is_motus_rk4("oscillator"); }
// (Kepler and Lorenz have right-hand sides written for Odeint: the same formula, the same numbers.)
// Lorenz is chaotic: a rounding of 1e-15 in its state (|x| ~ 10) grows as e^(λt), λ = 0.906 (its
// largest Lyapunov exponent, tests/reference/integrators.md), to 1e-15·e^9.06 ≈ 9e-12 at t = 10
// (measured 1.3e-12 at h = 0.00025).
TEST(OdeintPeer, Rk4AtAFixedStepIsMotusRk4OnLorenz) { expect_odeint_rk4_is_motus_rk4("lorenz", 1e-15 * std::exp(0.906 * 10)); }

TEST(OdeintPeer, EveryStepperRunsKeplerAndTheSymplecticOneOnlyMechanicalScenes) {
  const SceneDescription kepler = shipped("kepler");
  const auto curves = precision::sweep_odeint(kepler, short_sweep(kepler, 3));
  std::set<std::string> names;
  for (const auto& c : curves) {
    names.insert(c.method);
    EXPECT_EQ(c.unsupported, "") << c.method;
    EXPECT_EQ(c.engine, "odeint");
  }
  EXPECT_EQ(names, (std::set<std::string>{"odeint:runge_kutta4", "odeint:runge_kutta_dopri5", "odeint:runge_kutta_fehlberg78",
                                          "odeint:symplectic_rkn_sb3a_mclachlan"}));
  // Controlled steppers: a tighter tolerance, a smaller error. Ten decades of tolerance (1e-3 against
  // 1e-13) give a fifth-order pair at least six decades of error (measured 9.5e-11 for dopri5 and 8.5e-9
  // for rkf78, whose 1e-3 point is already accurate), as the error follows the tolerance.
  for (const char* m : {"odeint:runge_kutta_dopri5", "odeint:runge_kutta_fehlberg78"}) {
    const auto& c = curve_named(curves, m);
    ASSERT_GE(c.points.size(), 2u);
    EXPECT_LT(c.points.back().error, 1e-6 * c.points.front().error) << m;
    EXPECT_DOUBLE_EQ(c.points.back().t_end, kepler.start_time + kepler.duration) << "lands on the end";
  }
  // McLachlan's RKN is of order 4 (measured 3.9996 between h = 0.005 and 0.0025, where the error is
  // still far above rounding).
  const auto& rkn = curve_named(curves, "odeint:symplectic_rkn_sb3a_mclachlan");
  EXPECT_NEAR(std::log2(rkn.points[1].error / rkn.points[2].error), 4.0, 0.1);

  const SceneDescription lorenz = shipped("lorenz");
  const auto first_order = precision::sweep_odeint(lorenz, short_sweep(lorenz, 1));
  EXPECT_NE(curve_named(first_order, "odeint:symplectic_rkn_sb3a_mclachlan").unsupported, "");
  EXPECT_EQ(curve_named(first_order, "odeint:runge_kutta4").unsupported, "");
}

// ---------------------------------------------------------------------------------------------------------
// Box2D and Bullet: semi-implicit Euler.

// tolerance: of the error at dt = 1/60; ratio_tolerance: of each halving's ratio (Box2D's float state
// rounds more at the smaller steps).
void expect_free_fall_error_of_symplectic_euler(const std::string& engine, double tolerance, double ratio_tolerance) {
  const SceneDescription s = shipped("free_fall");
  const double g = 9.81, h = 1.0 / 60;
  const precision::Curve c = precision::sweep_engine(s, engine, short_sweep(s, 1));
  ASSERT_EQ(c.unsupported, "") << engine;
  ASSERT_EQ(c.points.size(), precision::engine_steps().size());
  const precision::Point* at_60 = nullptr;
  for (const auto& p : c.points)
    if (p.h == h) at_60 = &p;
  ASSERT_NE(at_60, nullptr);
  EXPECT_EQ(at_60->steps, 120);
  EXPECT_DOUBLE_EQ(at_60->t_end, 2.0);
  EXPECT_NEAR(at_60->error, 0.5 * g * h * at_60->t_end, tolerance) << engine;  // 0.1635 m
  // And motus's own symplectic Euler at the same step, the same error.
  const precision::Curve motus = precision::sweep_motus(s, Integrator::SymplecticEuler, [&] {
    auto sweep = short_sweep(s, 1);
    sweep.dt = h;
    return sweep;
  }());
  EXPECT_NEAR(motus.points.at(0).error, 0.5 * g * h * 2.0, 1e-12);
  // Error ∝ dt: every halving halves it.
  for (size_t i = 1; i < c.points.size(); ++i)
    EXPECT_NEAR(c.points[i - 1].error / c.points[i].error, 2.0, ratio_tolerance) << engine << " at dt = " << c.points[i].h;
}

TEST(EnginePeers, Box2dFallsAsSymplecticEulerDoes) { expect_free_fall_error_of_symplectic_euler("box2d", 1e-4, 0.05); }  // float
TEST(EnginePeers, BulletFallsAsSymplecticEulerDoes) { expect_free_fall_error_of_symplectic_euler("bullet", 1e-9, 1e-6); }

TEST(EnginePeers, WhatAnEngineCannotRunIsSaid) {
  SceneDescription oscillator = shipped("oscillator");  // made 3-D: Box2D is a 2-D engine
  oscillator.mechanical->dimensions = 3;
  for (auto& b : oscillator.mechanical->bodies) {
    b.position.resize(3, 0.0);
    b.velocity.resize(3, 0.0);
  }
  const precision::Curve c = precision::sweep_engine(oscillator, "box2d", short_sweep(oscillator, 1));
  EXPECT_NE(c.unsupported.find("3-D"), std::string::npos) << c.unsupported;
  EXPECT_TRUE(c.points.empty());
}

// ---------------------------------------------------------------------------------------------------------
// Reading a curve at a target error.

TEST(Targets, InterpolatesOnLogLogAxes) {
  precision::Curve c;
  auto point = [](double error, double seconds, long evaluations) {
    precision::Point p;
    p.error = error;
    p.seconds = p.median_seconds = seconds;
    p.evaluations = evaluations;
    return p;
  };
  c.points = {point(1e-2, 1e-6, 100), point(1e-6, 1e-4, 10000)};  // error ∝ time⁻²
  // The median runs are read off the same way, on their own: here 3 times the fastest at one point and
  // 12 times at the other, so that at the target, halfway on log axes, √(3 · 12) = 6 times 1e-5.
  c.points[0].median_seconds = 3e-6;
  c.points[1].median_seconds = 12e-4;
  const auto at = precision::at_target(c, 1e-4);
  ASSERT_TRUE(at);
  EXPECT_NEAR(at->seconds, 1e-5, 1e-18);
  EXPECT_NEAR(at->median_seconds, 6e-5, 1e-17);
  EXPECT_NEAR(at->evaluations, 1000, 1e-9);
  EXPECT_FALSE(at->upper_bound);
  EXPECT_TRUE(precision::at_target(c, 1e-1)->upper_bound);
  EXPECT_FALSE(precision::at_target(c, 1e-7));
  // Not monotone (an adaptive method's lucky dip at 1e-5): read where it stays below for good.
  c.points = {point(1e-2, 1e-6, 100), point(1e-5, 2e-6, 200), point(1e-3, 1e-5, 1000), point(1e-5, 1e-4, 10000)};
  const auto for_good = precision::at_target(c, 1e-4);
  ASSERT_TRUE(for_good);
  EXPECT_NEAR(for_good->evaluations, 1000 * std::pow(10.0, 0.5), 1e-6);  // halfway from 1e-3 to 1e-5
  EXPECT_FALSE(precision::at_target(c, 1e-6));
  // A method whose steps evaluate nothing (symplectic Euler among collisions alone) is read too.
  c.points = {point(1e-13, 1e-6, 0), point(1e-14, 2e-6, 0)};
  const auto no_evaluations = precision::at_target(c, 1e-10);
  ASSERT_TRUE(no_evaluations);
  EXPECT_TRUE(no_evaluations->upper_bound);
  EXPECT_EQ(no_evaluations->evaluations, 0);
}

// ---------------------------------------------------------------------------------------------------------
// The command.

std::vector<std::vector<std::string>> csv_rows(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

TEST(BenchPrecisionCommand, WritesTheRunFolderWithEveryMethodAndPeer) {
  TempDir dir;
  const fs::path out = dir / "kepler-run";
  const auto r = run_motus(dir, {"bench", "precision", "kepler", "--peers", "odeint,box2d,bullet", "--levels", "2",
                                 "--per-decade", "1", "--repeats", "1", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* file : {"index.html", "precision.csv", "targets.csv", "error_against_time.png", "error_against_time.svg",
                           "error_against_evaluations.png", "error_against_evaluations.svg"})
    EXPECT_TRUE(fs::is_regular_file(out / file) && fs::file_size(out / file) > 0) << file;

  const auto rows = csv_rows(read_file(out / "precision.csv"));
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(rows[0], (std::vector<std::string>{"scene", "integrator", "h", "tolerance", "steps", "evaluations", "t_end",
                                               "error", "seconds", "engine", "failed", "median_seconds"}));
  std::map<std::string, int> points;  // method → points
  std::map<std::string, std::string> engine_of;
  for (size_t i = 1; i < rows.size(); ++i) {
    ASSERT_GE(rows[i].size(), 11u) << i;
    ++points[rows[i][1]];
    engine_of[rows[i][1]] = rows[i][9];
  }
  for (const char* m : {"euler", "rk4", "rk45", "dop853", "symplectic-euler", "velocity-verlet"})
    EXPECT_EQ(engine_of[m], "motus") << m;
  EXPECT_EQ(points["rk4"], 2);          // --levels 2
  EXPECT_EQ(points["dop853"], 11);      // 1e-3 … 1e-13, one per decade
  for (const char* m : {"odeint:runge_kutta4", "odeint:runge_kutta_dopri5", "odeint:runge_kutta_fehlberg78",
                        "odeint:symplectic_rkn_sb3a_mclachlan"})
    EXPECT_EQ(engine_of[m], "odeint") << m;
  EXPECT_EQ(points["box2d"], 6);  // dt = 1/30 … 1/960
  EXPECT_EQ(points["bullet"], 6);

  // The targets table, in the terminal and on the page.
  EXPECT_NE(r.out.find("targets:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("motus/odeint"), std::string::npos) << r.out;
  const std::string html = read_file(out / "index.html");
  EXPECT_NE(html.find("Targets"), std::string::npos);
  EXPECT_NE(html.find("error_against_time.svg"), std::string::npos);
  EXPECT_NE(html.find("odeint:runge_kutta_fehlberg78"), std::string::npos);
}

// The progress bar counts steps, not points, and leaves out what cannot run the scene: counted in
// points, arenstorf's bar stood at 15 % for most of its 89 s (each level has twice the steps of the
// one before), and a first-order system's bar ended at 63 % (its five symplectic methods counted).
TEST(BenchPrecisionCommand, ItsProgressIsTheWorkDoneAndReachesTheEnd) {
  TempDir dir;
  const auto r = run_motus(dir,
                           {"bench", "precision", "lorenz_equations", "--levels", "6", "--per-decade", "1", "--repeats", "1",
                            "--out", (dir / "run").string()},
                           {"MOTUS_PROGRESS=every", "COLUMNS=80"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<int> percents;  // every value the bar showed, in order
  const std::regex percent(R"((\d+)%)");
  for (auto it = std::sregex_iterator(r.err.begin(), r.err.end(), percent); it != std::sregex_iterator(); ++it)
    if (const int p = std::stoi((*it)[1].str()); percents.empty() || p != percents.back()) percents.push_back(p);
  ASSERT_GE(percents.size(), 7u) << r.err;
  EXPECT_EQ(percents.back(), 100) << r.err;
  // The work in units of the first level's steps: euler, midpoint and rk4 six levels each, 1 + 2 + … +
  // 32 = 63 units; rk4-doubling, rk45 and dop853 eleven tolerances each, counted at one unit (their
  // first step is the scene's dt): 3 · 63 + 3 · 11 = 222, done once in the untimed round and once in
  // the one timed round (--repeats 1): 444. Euler comes first in the untimed round: after its levels
  // the bar shows 100 · (1, 3, 7, 15, 31, 63) / 444 % (the first, 0.23 %, as the start's 0 %).
  const std::vector<double> euler = {0, 100.0 * 3 / 444, 100.0 * 7 / 444, 100.0 * 15 / 444, 100.0 * 31 / 444, 100.0 * 63 / 444};
  for (size_t k = 0; k < euler.size(); ++k) EXPECT_NEAR(percents[k], euler[k], 1.0) << k << "\n" << r.err;
}

// A pictures audit: symplectic Euler's two forms (and Verlet's two) lie on each other on Kepler (the same
// evaluations, errors 0.2 % apart), and the legend showed four methods where two lines could be seen. The
// later one says whose line it lies on; a method on a line of its own says nothing more.
TEST(BenchPrecisionCommand, ALineDrawnOnAnotherSaysWhose) {
  TempDir dir;
  const auto r = run_motus(dir, {"bench", "precision", "kepler", "--integrators",
                                 "symplectic-euler,symplectic-euler-x,verlet,velocity-verlet,rk4", "--levels", "2",
                                 "--per-decade", "1", "--repeats", "1", "--out", (dir / "run").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string script = read_file(dir / "run" / "figures.gp");
  EXPECT_NE(script.find("title 'symplectic-euler-x (on symplectic-euler''s line)'"), std::string::npos) << script;
  EXPECT_NE(script.find("title 'velocity-verlet (on verlet''s line)'"), std::string::npos) << script;
  EXPECT_NE(script.find("title 'rk4'"), std::string::npos) << script;
  EXPECT_EQ(script.find("rk4 (on"), std::string::npos) << script;
}

TEST(BenchPrecisionCommand, APeerThatCannotRunTheSceneIsReported) {
  TempDir dir;
  const fs::path out = dir / "lorenz-run";
  const auto r = run_motus(dir, {"bench", "precision", "lorenz", "--peers", "box2d,bullet", "--integrators", "rk4",
                                 "--levels", "1", "--repeats", "1", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* engine : {"box2d", "bullet"}) {
    bool said = false;
    std::stringstream lines(r.out);
    for (std::string line; std::getline(lines, line);)
      said = said || (line.rfind(engine, 0) == 0 && line.find("cannot run this scene") != std::string::npos);
    EXPECT_TRUE(said) << engine << "\n" << r.out;
  }
  EXPECT_NE(read_file(out / "index.html").find("cannot run this scene"), std::string::npos);
  // The targets table says it too, as the page does (it said "not reached").
  const size_t targets = r.out.find("targets:");
  ASSERT_NE(targets, std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cannot run this scene", targets), std::string::npos) << r.out.substr(targets);
}

TEST(BenchPrecisionCommand, MethodsThatCannotRunCollisionsAreReported) {
  TempDir dir;
  const auto r = run_motus(dir, {"bench", "precision", "head_on", "--integrators", "rk4,symplectic-euler", "--peers",
                                 "odeint", "--levels", "1", "--repeats", "1", "--out", (dir / "run").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* method : {"rk4", "odeint:runge_kutta4", "odeint:runge_kutta_fehlberg78"}) {
    bool said = false;
    std::stringstream lines(r.out);
    for (std::string line; std::getline(lines, line);)
      said = said || (line.rfind(std::string(method) + " ", 0) == 0 && line.find("cannot run this scene") != std::string::npos);
    EXPECT_TRUE(said) << method << "\n" << r.out;
  }
  EXPECT_NE(read_file(dir / "run" / "precision.csv").find(",symplectic-euler,"), std::string::npos);
  // Its steps evaluate no force (collisions alone): its errors, rounding's (~1e-14), still meet
  // every target, and the figure of evaluations says why it is not drawn there.
  EXPECT_NE(read_file(dir / "run" / "targets.csv").find("1e-10,symplectic-euler,motus,"), std::string::npos);
  EXPECT_NE(read_file(dir / "run" / "figures.gp").find("evaluate no force here: symplectic-euler"), std::string::npos);
}

// Found by an audit of the pictures: a line's colour went by its place among the curves drawn, so
// Bullet's was motus's blue (and euler's, in the same diagram) with Box2D, Bullet and Odeint as
// peers, dark red with Box2D and Bullet alone. Box2D and Bullet now have compare's colours
// (report.cpp: orange and green), each method the same line whoever else ran, no two alike.
TEST(BenchPrecisionCommand, EachMethodKeepsItsLineWhoeverElseRan) {
  TempDir dir;
  std::map<std::string, std::string> first_run;
  for (const char* peers : {"box2d,bullet,odeint", "bullet"}) {
    const fs::path out = dir / (std::string("run-") + peers);
    const auto r = run_motus(dir, {"bench", "precision", "free_fall", "--peers", peers, "--levels", "1", "--repeats", "1",
                                   "--out", out.string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const std::string gp = read_file(out / "figures.gp");
    const std::string first = gp.substr(0, gp.find("set terminal svg"));  // the first figure's plot line
    const std::regex entry(R"(lc rgb '(#[0-9a-f]{6})'((?: dt (?:\d|\([0-9,]+\)))?) title '([^']+)')");
    std::map<std::string, std::string> line_of;
    std::set<std::string> looks;
    for (auto it = std::sregex_iterator(first.begin(), first.end(), entry); it != std::sregex_iterator(); ++it) {
      line_of[(*it)[3].str()] = (*it)[1].str() + (*it)[2].str();
      looks.insert((*it)[1].str() + (*it)[2].str());
    }
    ASSERT_TRUE(line_of.count("bullet") && line_of.count("euler")) << gp;
    EXPECT_EQ(line_of["bullet"].substr(0, 7), "#43a360") << peers;
    if (line_of.count("box2d")) {
      EXPECT_EQ(line_of["box2d"].substr(0, 7), "#df7430") << peers;
    }
    EXPECT_EQ(looks.size(), line_of.size()) << "two lines look alike:\n" << first;
    if (first_run.empty()) {
      first_run = line_of;
    } else {
      for (const auto& [method, line] : line_of) EXPECT_EQ(line, first_run[method]) << method;
    }
  }
}

TEST(BenchPrecisionCommand, BadPeersAndFlagsAreOneLineExitTwo) {
  TempDir dir;
  fs::create_directories(dir / "exists");
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--peers", "odeint,nosuch"}, std::vector<std::string>{"--peers", ""},
        std::vector<std::string>{"--peers", "box2d,,odeint"}, std::vector<std::string>{"--targets", "1e-4,,1e-6"},
        std::vector<std::string>{"--targets", "0"}, std::vector<std::string>{"--targets", "abc"},
        std::vector<std::string>{"--per-decade", "0"}, std::vector<std::string>{"--levels", "0"},
        std::vector<std::string>{"--repeats", "0"}, std::vector<std::string>{"--duration", "-1"},
        std::vector<std::string>{"--integrators", "nosuch"},
        std::vector<std::string>{"--out", (dir / "exists").string()},
        // (a copy inside the run's folder: refused before the run, not found there after it)
        std::vector<std::string>{"--out", (dir / "run").string(), "--csv", (dir / "run" / "copy.csv").string()},
        // ("-" is standard output to `motus run --trajectory`: here it made a file called "-")
        std::vector<std::string>{"--csv", "-"},
        std::vector<std::string>{"--set", "start_time=1e17"},  // (times 16 apart: the runs never got there)
        std::vector<std::string>{"--duration", "1e300"}}) {
    std::vector<std::string> args = {"bench", "precision", "kepler", "--levels", "1", "--repeats", "1"};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = run_motus(dir, args);
    EXPECT_EQ(r.status, 2) << extra[0] << " " << extra[1] << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << extra[0] << ": " << r.err;
    EXPECT_EQ(r.err.rfind("motus: error: ", 0), 0u) << r.err;
  }
  EXPECT_TRUE(fs::is_empty(dir / "exists")) << "an existing --out is left alone";
  EXPECT_FALSE(fs::exists(dir / "run"));
  EXPECT_FALSE(fs::exists(dir / "-"));
}

TEST(BenchPrecisionCommand, FixedStepsLandOnASceneKnownOnlyAtItsReferenceTime) {
  // arenstorf is known only at T = 17.0652165601579625588917206249 (its reference state): each
  // fixed step is shortened to divide T, so rk4 at the scene's dt = 0.001 takes ceil(T/0.001) =
  // 17066 steps and ends on T (it ended at 17.066, where nothing is known, and the command failed).
  // Named twice, it is one curve.
  TempDir dir;
  const auto r = run_motus(dir, {"bench", "precision", "arenstorf", "--integrators", "rk4,rk4", "--levels", "1",
                                 "--repeats", "1", "--out", (dir / "a").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream csv(read_file(dir / "a" / "precision.csv"));
  std::string header, row, extra;
  std::getline(csv, header);
  ASSERT_TRUE(std::getline(csv, row));
  EXPECT_FALSE(std::getline(csv, extra)) << "one curve of one point: " << extra;
  std::vector<std::string> cells;
  std::istringstream cell_stream(row);
  for (std::string cell; std::getline(cell_stream, cell, ',');) cells.push_back(cell);
  ASSERT_GE(cells.size(), 8u) << row;
  EXPECT_EQ(cells[4], "17066") << row;                              // steps
  EXPECT_NEAR(std::stod(cells[6]), 17.0652165601579625588917206249, 1e-9) << row;  // t_end
  // An error was measured there (its size is the curves' to show: 0.91 here, Arenstorf's orbit
  // being hard on fixed steps; not this test's).
  EXPECT_TRUE(std::isfinite(std::stod(cells[7])) && std::stod(cells[7]) > 0) << row;
}

// Odeint's fixed steps land there too, with the same h: its runge_kutta4 ran to 17.066 and the
// whole command failed ("no reference state at t = 17.066000", exit 1). On the same right-hand
// side with the same steps it gives motus's rk4's numbers.
TEST(BenchPrecisionCommand, OdeintsFixedStepsLandOnTheReferenceTimeToo) {
  TempDir dir;
  const auto r = run_motus(dir, {"bench", "precision", "arenstorf", "--integrators", "rk4", "--peers", "odeint", "--levels",
                                 "1", "--per-decade", "1", "--repeats", "1", "--out", (dir / "a").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  std::map<std::string, std::vector<std::string>> rows;  // method → its one row
  std::istringstream csv(read_file(dir / "a" / "precision.csv"));
  for (std::string line; std::getline(csv, line);) {
    std::vector<std::string> cells;
    std::istringstream cell_stream(line);
    for (std::string cell; std::getline(cell_stream, cell, ',');) cells.push_back(cell);
    if (cells.size() >= 8 && (cells[1] == "rk4" || cells[1] == "odeint:runge_kutta4")) rows[cells[1]] = cells;
  }
  ASSERT_EQ(rows.size(), 2u) << read_file(dir / "a" / "precision.csv");
  EXPECT_EQ(rows["odeint:runge_kutta4"][2], rows["rk4"][2]);  // h
  EXPECT_EQ(rows["odeint:runge_kutta4"][4], "17066");         // steps
  EXPECT_NEAR(std::stod(rows["odeint:runge_kutta4"][7]), std::stod(rows["rk4"][7]), 1e-9 * std::stod(rows["rk4"][7]));
}

// A ratio where one side's time is only a bound (its cheapest point already below the target)
// is a bound itself, and where both are, none: free fall is exact for both adaptive methods.
TEST(Targets, ARatioWithABoundIsABound) {
  const precision::Fastest bound{"a", {1e-6, 1e-6, 10, true}}, exact{"b", {2e-6, 2e-6, 20, false}};
  EXPECT_EQ(precision::ratio_text(bound, exact, true), "<=0.50 (0.50)");
  EXPECT_EQ(precision::ratio_text(exact, bound, true), ">=2.00 (2.00)");
  EXPECT_EQ(precision::ratio_text(bound, bound, true), "-");
  EXPECT_EQ(precision::ratio_text(exact, exact, true), "1.00 (1.00)");
  EXPECT_EQ(precision::ratio_text(std::nullopt, exact, true), "-");
  // Far below one: two significant figures, not two decimals (motus 0.81 µs against Bullet's
  // 1,030 µs printed 0.00).
  const precision::Fastest quick{"c", {0.81e-6, 0.81e-6, 10, false}}, slow{"d", {1030e-6, 1030e-6, 20, false}};
  EXPECT_EQ(precision::ratio_text(quick, slow, true), "0.00079 (0.00079)");
}

// Curves as the bench measured them (an audit's runs): every method's error rises again at its most
// expensive points, where rounding takes over — that does not undo the cheaper points that reached
// the target (rk4 on the oscillator got to 8.7e-15, 1e-15 and 2.2e-16, then 1.2e-14 at its finest
// step, and was "not reached" at 3e-15); a lone point below among points above is luck, not a
// method that gets there (Bullet's head_on: exact at its cheapest dt, 0.3 m off at the next three);
// and a point after a blow-up has nothing to interpolate from: its time is a bound.
TEST(Targets, ARiseAtTheExpensiveEndKeepsWhatWasReachedAndALonePointBelowIsLuck) {
  auto curve = [](std::vector<double> errors) {
    precision::Curve c;
    double seconds = 1e-6;
    for (double e : errors) {
      precision::Point p;
      p.error = e;
      p.seconds = p.median_seconds = seconds;
      p.evaluations = static_cast<long>(seconds * 1e8);
      c.points.push_back(p);
      seconds *= 2;
    }
    return c;
  };
  const auto rk4 = curve({1e-9, 1e-11, 1e-13, 8.7e-15, 1e-15, 2.2e-16, 1.18e-14});
  for (const double target : {1e-14, 3e-15, 1e-15}) {
    const auto at = precision::at_target(rk4, target);
    ASSERT_TRUE(at) << target;
    EXPECT_FALSE(at->upper_bound) << target;
  }
  // 3e-15: between 8.7e-15 (8 µs) and 1e-15 (16 µs) on log–log axes.
  const double f = std::log(3e-15 / 8.7e-15) / std::log(1e-15 / 8.7e-15);
  EXPECT_NEAR(precision::at_target(rk4, 3e-15)->seconds, 8e-6 * std::pow(2.0, f), 1e-18);
  EXPECT_FALSE(precision::at_target(rk4, 1e-16));  // never got there

  const auto bullet = curve({2.58e-14, 0.3, 0.3, 0.3, 6.89e-12, 0.3});
  EXPECT_FALSE(precision::at_target(bullet, 1e-3));

  const auto blown_up = curve({INFINITY, 2.464, 2.0});
  const auto after = precision::at_target(blown_up, 3);
  ASSERT_TRUE(after);
  EXPECT_TRUE(after->upper_bound);
  EXPECT_DOUBLE_EQ(after->seconds, 2e-6);
}

// Found by an accessibility audit: no <html lang> or viewport, tables without named headers, two
// columns both headed "µs" (whose?), "–" for a target not reached, and times without units.
TEST(BenchPrecisionCommand, ThePageIsNamedItsTablesHaveHeadersAndItsTimesUnits) {
  TempDir dir;
  const fs::path out = dir / "kepler-run";
  const auto r = run_motus(dir, {"bench", "precision", "kepler", "--peers", "odeint", "--integrators", "euler,rk4",
                                 "--levels", "2", "--per-decade", "1", "--repeats", "1", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = read_file(out / "index.html");
  EXPECT_TRUE(starts_as_a_page(html));
  EXPECT_TRUE(tables_have_headers(html));
  for (const char* engine : {"motus", "odeint"})
    EXPECT_NE(html.find("<th scope=\"col\">" + std::string(engine) + " µs</th>"), std::string::npos) << engine;
  EXPECT_TRUE(std::regex_search(html, std::regex(R"(From t = [0-9.e+-]+ s to t = [0-9.e+-]+ s;)")));
  EXPECT_TRUE(std::regex_search(html, std::regex(R"(\(dt = [0-9.e+-]+ s, k = 0)")));
  // Euler at two levels reaches none of the finer targets: said in words, in every method's table.
  const size_t every = html.find("Every method at every target");
  ASSERT_NE(every, std::string::npos);
  const std::string table = html.substr(every, html.find("</table>", every) - every);
  EXPECT_NE(table.find("<td>not reached</td>"), std::string::npos) << table;
  EXPECT_EQ(table.find("–"), std::string::npos) << table;
}

// ---------------------------------------------------------------------------------------------------------
// The timing rounds: an untimed round gives every point its numbers, then each timed round runs every
// method once more, the methods taking turns (each round one further on), so that a slow spell of a
// shared machine falls on all of them alike; a point's time is the fastest of its timed runs, the
// median beside it. (Before, each method ran all of its timed runs in a row, motus's before Odeint's.)
// Here the sweeps are stand-ins that say which round called them and give each point a time the
// test chooses, so the fastest and median are known.
TEST(TimingRounds, TheNumbersAreTheUntimedRoundsAndTheTimesTheFastestOfTheTimedOnes) {
  std::vector<std::string> calls;  // "a0", "b0", "a1", …: which sweep ran for which round
  auto stand_in = [&](const std::string& name, double error, std::vector<double> seconds_by_round,
                      bool unsupported = false) -> precision::SweepOf {
    return [&calls, name, error, seconds_by_round, unsupported](const precision::Sweep& s) {
      calls.push_back(name + std::to_string(s.round));
      precision::Curve c;
      c.method = c.engine = name;
      if (unsupported) {
        c.unsupported = "cannot";
        return std::vector{c};
      }
      precision::Point p;
      // Later rounds give another error: only the untimed round's may be reported.
      p.error = s.round == 0 ? error : 1.0;
      p.seconds = p.median_seconds = seconds_by_round.at(static_cast<size_t>(s.round));
      c.points = {p};
      return std::vector{c};
    };
  };
  precision::Sweep sweep;
  sweep.repeats = 4;
  const auto curves = precision::sweep_in_rounds(
      {stand_in("a", 1e-6, {99, 5, 3, 4, 8}), stand_in("b", 1e-7, {99, 2, 6, 1, 7}), stand_in("c", 0, {}, true)},
      sweep);
  // Round 0 in order; then a, b in turns, each timed round beginning one further on (c, which cannot
  // run the scene, has nothing to time and runs in the untimed round only).
  EXPECT_EQ(calls, (std::vector<std::string>{"a0", "b0", "c0", "a1", "b1", "b2", "a2", "a3", "b3", "b4", "a4"}));
  ASSERT_EQ(curves.size(), 3u);
  EXPECT_EQ(curves[0].method, "a");
  EXPECT_EQ(curves[0].points.at(0).error, 1e-6);
  EXPECT_EQ(curves[0].points.at(0).seconds, 3);           // of 5, 3, 4, 8 (never the untimed 99)
  EXPECT_EQ(curves[0].points.at(0).median_seconds, 4.5);  // (4 + 5) / 2
  EXPECT_EQ(curves[1].points.at(0).error, 1e-7);
  EXPECT_EQ(curves[1].points.at(0).seconds, 1);
  EXPECT_EQ(curves[1].points.at(0).median_seconds, 4);  // (2 + 6) / 2
  EXPECT_EQ(curves[2].unsupported, "cannot");
}

// The order of both commands' timing rounds (compare/timing.hpp, used by compare's rounds and these):
// every engine once a round, each round beginning one further on, so that whatever disturbs a
// round's start does not always fall on the same engine. (The order of three engines, written out.)
TEST(TimingRounds, EveryEngineTakesItsTurnOnceARoundAndEachRoundBeginsOneFurtherOn) {
  const std::vector<std::vector<size_t>> expected = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 1, 2}};
  for (size_t round = 0; round < expected.size(); ++round)
    for (size_t turn = 0; turn < 3; ++turn)
      EXPECT_EQ(compare::taking_turns(3, round, turn), expected[round][turn]) << "round " << round << ", turn " << turn;
  EXPECT_EQ(compare::taking_turns(1, 5, 0), 0u);
}

// What the table says beside "not reached": the smallest error any point of the engine reached, so
// that a reader can tell a method that stops short of a target from a sweep that ends before it
// (an audit: arenstorf's rkf78 reaches 6.7e-10 at a tolerance of 1e-14, past the sweep's 1e-13).
TEST(Targets, NotReachedSaysTheSmallestErrorReached) {
  precision::Curve a, b;
  a.engine = b.engine = "odeint";
  for (double e : {1e-3, 6.7e-10, 2e-9}) {
    precision::Point p;
    p.error = e;
    a.points.push_back(p);
  }
  precision::Point failed;
  failed.error = 1e-12;  // (a failed point's numbers are not a result)
  failed.failed = "underflow";
  b.points = {failed};
  EXPECT_EQ(precision::not_reached_text({a, b}, "odeint", true), "not reached (best 6.7e-10)");
  EXPECT_EQ(precision::not_reached_text({a, b}, "odeint"), "not reached (best 6.7e−10)");
  EXPECT_EQ(precision::not_reached_text({b}, "odeint", true), "not reached");
}

// The page speaks of the peers that ran only (it described Box2D's and Bullet's steps and semi-implicit
// Euler on a run of motus and Odeint), and says how busy the machine was while the points were timed
// (MOTUS_LOADAVG's file: the test does not depend on this machine's load), warning when busier than
// its cores, as compare does.
TEST(BenchPrecisionCommand, ThePageSaysOnlyThePeersThatRanAndHowBusyTheMachineWas) {
  TempDir dir;
  const long cores = ::sysconf(_SC_NPROCESSORS_ONLN);
  ASSERT_GT(cores, 0);
  const fs::path busy = dir / "busy.loadavg";
  write_file(busy, std::to_string(cores) + ".50 0.50 0.40 2/345 6789\n");
  const fs::path out = dir / "kepler-run";
  const auto r = run_motus(dir, {"bench", "precision", "kepler", "--peers", "odeint", "--integrators", "rk4", "--levels",
                                 "1", "--per-decade", "1", "--repeats", "1", "--out", out.string()},
                           {"MOTUS_LOADAVG=" + busy.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = read_file(out / "index.html");
  EXPECT_EQ(html.find("Box2D"), std::string::npos) << html;
  EXPECT_EQ(html.find("Bullet"), std::string::npos) << html;
  EXPECT_NE(html.find("Odeint's steppers"), std::string::npos);
  const std::string load = "The machine's 1-minute load average was " + std::to_string(cores) + ".50 as the timing began and " +
                           std::to_string(cores) + ".50 as it ended, on " + std::to_string(cores) + " core";
  EXPECT_NE(html.find(load), std::string::npos) << html;
  EXPECT_NE(html.find("<strong>Warning:</strong> the timings were taken on a busy machine"), std::string::npos) << html;
  EXPECT_NE(r.out.find(load), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("warning: the timings were taken on a busy machine"), std::string::npos) << r.out;
  // (Found by an audit: the targets' paragraph had lost words — "the smallest error any of the  from the
  // fastest runs". The page's prose has no doubled space where a word went missing.)
  EXPECT_NE(html.find("the smallest error any of the engine's points reached is given in brackets"), std::string::npos);
  const std::string prose = html.substr(0, html.find("<table"));
  EXPECT_EQ(prose.find(" the  "), std::string::npos) << prose;
  EXPECT_EQ(html.find(" of the  "), std::string::npos);
}

}  // namespace
