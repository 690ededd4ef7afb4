// `motus stress` through the command line (docs/cli.md, "motus stress"):
//   - on the oscillator (x'' = −x, ω = 1), the measured largest stable steps are where theory says a
//     trial of N steps first passes the blow-up factor F, to the search's bisection (2⁻²⁴ relative):
//     near ωh = 2 for both symplectic Eulers (their modified energy passes 1 + F at 2F/(F + 1)) and
//     both Verlets (just above 2, by their growth there), above 2√2 for RK4, and where their per-step
//     growth takes explicit Euler and midpoint, unstable at every h, past the factor
//     (tests/reference/integrators.md, "Stability on x'' = −ω²x");
//   - on the plotted drift (drift.csv), explicit Euler's energy grows exactly as theory says,
//     E/E0 = (1 + z²)^n with z = ωh (integrators.md), and the symplectic methods stay bounded: the last
//     tenth of the run no worse than 1.5 × its first hundredth, and within the bound of their modified
//     energies (integrators.md: E_max/E_min = (1 + z/2)/(1 − z/2) for symplectic Euler, 1/(1 − z²/4)
//     for velocity Verlet);
//   - oscillator, kepler, ball_gas and cloth each produce their page (index.html, CSV, SVG and PNG);
//   - on ball_gas, symplectic Euler's collisions match the course's 1-D collision formula
//     (docs/course.md, section 9) at every mass ratio, and nothing tunnels at any speed;
//   - bad input is one line and exit status 2; Ctrl-C exits 130 and leaves no folder.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <regex>
#include <set>
#include <sstream>

#include "accessibility.hpp"
#include "cli_harness.hpp"

namespace {

using namespace motus_test;

// A page made by `motus stress SCENE --out DIR/SCENE` (ctest runs each test in a process of its
// own, so each test makes the page it looks at).
struct Page {
  fs::path folder;
  Result result;
  nlohmann::json summary;
};

Page make_page(const TempDir& dir, const std::string& scene) {
  Page p;
  p.folder = dir / scene;
  p.result = run_motus(dir, {"stress", scene, "--out", p.folder.string()});
  p.summary = nlohmann::json::parse(read_file(p.folder / "summary.json"), nullptr, false);
  return p;
}

void expect_page(const Page& p, const std::vector<std::string>& stems) {
  ASSERT_EQ(p.result.status, 0) << p.result.err;
  EXPECT_TRUE(p.result.err.empty()) << p.result.err;
  EXPECT_NE(p.result.out.find("page: " + p.folder.string() + "/index.html"), std::string::npos) << p.result.out;
  for (const auto& file : {"index.html", "summary.json", "figures.gp", "figures.dat"})
    EXPECT_TRUE(fs::is_regular_file(p.folder / file)) << file;
  for (const auto& stem : stems) {
    EXPECT_TRUE(fs::is_regular_file(p.folder / (stem + ".csv"))) << stem;
    for (const char* ext : {".svg", ".png"}) {
      const fs::path picture = p.folder / (stem + ext);
      EXPECT_TRUE(fs::is_regular_file(picture)) << picture;
      if (fs::is_regular_file(picture)) {
        EXPECT_GT(fs::file_size(picture), 1000u) << picture;
      }
    }
    EXPECT_NE(read_file(p.folder / "index.html").find(stem + ".svg"), std::string::npos) << stem;
  }
  ASSERT_FALSE(p.summary.is_discarded());
  for (const auto& stem : stems) EXPECT_TRUE(p.summary.contains(stem)) << stem;
}

// ---- the oscillator --------------------------------------------------------------------------

// The largest stable step is the last step a trial of N steps survives: |E − E0| ≤ F·|E0| after
// every step (stress_measures.cpp, blow_up). So the limit it measures is where the theory's energy
// after N steps first passes 1 + F — the textbook limit only where the energy jumps there. On the
// oscillator (ω = 1, from (x, v) = (1, 0)) each method's energy ratio is known in closed form
// (integrators.md, "Stability on x'' = −ω²x" and "The limits `motus stress` measures"):
//   - euler, midpoint, rk4: the step matrix is a scaled rotation, E_n/E0 = g^n with g = 1 + z²,
//     1 + z⁴/4 and 1 + z⁶(z² − 8)/576: the limit is g(z)^N = 1 + F (rk4 2.82870190, 9.7e-5
//     above 2√2, for N = 10⁴, F = 10⁶);
//   - the symplectic Eulers: bounded below z = 2, but E/E0 reaches 1/(1 − z/2) (their modified
//     energy), which passes 1 + F at z = 2F/(F + 1) = 1.999998;
//   - the Verlets: E/E0 ≤ 1 for z < 2; above it, with 2 − z² = −2 cosh s, E_n/E0 = cosh²(ns) +
//     sinh²(s/2)·sinh²(ns), which passes 1 + F at sinh(Ns)·cosh(s/2) = √F: z = 2 cosh(s/2) =
//     2.000000144.
// The search doubles h from dt/1024 until a trial blows up, then halves the bracket [a, 2a] it found
// 24 times (measure_stability): the last stable h and the first that blew up (first_blowup_h)
// end 2⁻²⁴·a ≤ 6e-8 of the limit apart, and the theory's limit must lie between them. (Rounding
// moves the engine's crossing far less: its energy after 10⁴ steps is off by some 10⁴ roundings,
// 1e-12 relative, and each method's energy changes by more than that over 1e-12 of its step; the
// closest a limit came to either end of its bracket is 2.7e-9, symplectic Euler's, of a 9.5e-8
// bracket.)
double verlet_limit(double n, double f) {  // z = 2 cosh(s/2) where sinh(N s)·cosh(s/2) = √F
  double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const double s = 0.5 * (lo + hi);
    (std::log(std::sinh(n * s)) + std::log(std::cosh(s / 2)) > 0.5 * std::log(f) ? hi : lo) = s;
  }
  const double q = std::sinh(lo / 4);
  return 2 + 4 * q * q;  // 2 cosh(s/2), without the rounding of 2 cosh(s/2) − 2 at 1e-7
}

double rk4_limit(double n, double f) {  // (1 + z⁶(z² − 8)/576)^N = 1 + F, above 2√2
  double lo = 2 * std::numbers::sqrt2, hi = 3;
  for (int i = 0; i < 200; ++i) {
    const double z = 0.5 * (lo + hi);
    (n * std::log1p(std::pow(z, 6) * (z * z - 8) / 576) > std::log1p(f) ? hi : lo) = z;
  }
  return lo;
}

void expect_limits_where_the_blow_up_rule_puts_them(const Page& p) {
  ASSERT_EQ(p.summary.at("omega").get<double>(), 1.0);  // scenes/oscillator.json: m = 1, k = 1
  const double n = p.summary.at("settings").at("steps").get<double>(), f = p.summary.at("settings").at("energy_factor").get<double>();
  const double growth = std::expm1(std::log1p(f) / n);  // the per-step growth that N steps take to 1 + F
  const std::map<std::string, double> theory = {
      {"symplectic-euler", 2 * f / (f + 1)}, {"symplectic-euler-x", 2 * f / (f + 1)},
      {"verlet", verlet_limit(n, f)},         {"velocity-verlet", verlet_limit(n, f)},
      {"rk4", rk4_limit(n, f)},               {"euler", std::sqrt(growth)},
      {"midpoint", std::pow(4 * growth, 0.25)},
  };
  std::map<std::string, std::pair<double, double>> measured;  // (last stable, first blown up) ω h
  for (const auto& s : p.summary.at("stability"))
    if (s.at("limit_omega_h").is_number() && s.at("first_blowup_h").is_number())
      measured[s.at("integrator").get<std::string>()] = {s.at("limit_omega_h").get<double>(), s.at("first_blowup_h").get<double>()};
  for (const auto& [integrator, z] : theory) {
    ASSERT_TRUE(measured.count(integrator)) << integrator;
    const auto [stable, blown] = measured[integrator];  // (ω = 1: first_blowup_h is its ω h)
    std::printf("  %-20s measured omega h = %.10f, theory %.10f, relative difference %.2e, bracket %.2e\n",
                integrator.c_str(), stable, z, std::abs(stable - z) / z, (blown - stable) / stable);
    EXPECT_LE(stable, z) << integrator;
    EXPECT_GE(blown, z) << integrator;
    EXPECT_LE(blown - stable, std::ldexp(stable, -24)) << integrator;  // 24 halvings of [a, 2a], a ≤ the limit
  }
  // The same numbers are in stability.csv, the table a user opens.
  const std::string csv = read_file(p.folder / "stability.csv");
  EXPECT_EQ(csv.rfind("integrator,limit_h,limit_omega_h,theory_omega_h,", 0), 0u) << csv;
  EXPECT_NE(csv.find("\nvelocity-verlet,"), std::string::npos);
}

struct DriftRow {
  long step;
  double t, error, window_max;
};

std::map<std::string, std::vector<DriftRow>> read_drift(const fs::path& file) {
  std::map<std::string, std::vector<DriftRow>> rows;
  std::istringstream in(read_file(file));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "integrator,step,t,energy_error,max_energy_error_since_previous_row");
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::string name, step, t, error, window;
    std::getline(cells, name, ',');
    std::getline(cells, step, ',');
    std::getline(cells, t, ',');
    std::getline(cells, error, ',');
    std::getline(cells, window, ',');
    rows[name].push_back({std::stol(step), std::stod(t), std::stod(error), std::stod(window)});
  }
  return rows;
}

void expect_euler_grows_and_symplectic_bounded(const Page& p) {
  const auto rows = read_drift(p.folder / "drift.csv");
  const long n = p.summary.at("settings").at("drift_steps").get<long>();
  ASSERT_GE(n, 100000);  // the issue: 10^5 to 10^7 steps
  const double z = 0.1;  // ω h: scenes/oscillator.json has ω = 1, dt = 0.1

  // Explicit Euler: E/E0 = (1 + z²)^n (integrators.md) at every plotted point, until it overflows.
  const auto& euler = rows.at("euler");
  ASSERT_GE(euler.size(), 50u);
  double previous = 0;
  for (const auto& r : euler) {
    if (!std::isfinite(r.error)) break;
    const double theory = std::pow(1 + z * z, static_cast<double>(r.step)) - 1;
    EXPECT_NEAR(r.error / theory, 1, 1e-9) << "step " << r.step;
    EXPECT_GT(r.error, previous) << "step " << r.step;
    previous = r.error;
  }
  EXPECT_GT(previous, 1e100);  // it grew without bound

  // The symplectic ones: bounded over the whole run, within their modified energies' bounds.
  auto largest = [&](const std::vector<DriftRow>& v, long from, long to) {
    double m = 0;
    for (const auto& r : v)
      if (r.step > from && r.step <= to) m = std::max(m, r.window_max);
    return m;
  };
  // The symplectic Eulers keep a modified energy E ∓ (h/2)·x·v (integrators.md), so E/E0 stays within
  // [1/(1 + z/2), 1/(1 − z/2)] of a start where x·v = 0, as the oscillator's (1, 0) is: the largest
  // |E/E0 − 1| is 1/(1 − z/2) − 1 (E_max/E_min − 1, twice it, would hold from any start).
  const std::map<std::string, double> bound = {
      {"symplectic-euler", 1 / (1 - z / 2) - 1},
      {"velocity-verlet", 1 / (1 - z * z / 4) - 1},
      {"symplectic-euler-x", 1 / (1 - z / 2) - 1},  // its mirror image
      {"verlet", 1 / (1 - z * z / 4) - 1},                    // the same positions as velocity Verlet
  };
  for (const auto& [integrator, b] : bound) {
    const auto& v = rows.at(integrator);
    EXPECT_EQ(v.back().step, n) << integrator;  // ran to the end
    const double first = largest(v, 0, n / 100), last = largest(v, n - n / 10, n), all = largest(v, 0, n);
    std::printf("  %-20s first hundredth %.4e, last tenth %.4e, bound %.4e\n", integrator.c_str(), first, last, b);
    EXPECT_LE(last, 1.5 * first) << integrator;  // bounded
    EXPECT_LE(all, b * (1 + 1e-6)) << integrator;
  }
}

TEST(StressPages, OscillatorLimitsAreWhereTheBlowUpRuleSaysAndItsDrift) {
  TempDir dir;
  const Page p = make_page(dir, "oscillator");
  expect_page(p, {"stability", "drift", "stiffness"});
  ASSERT_EQ(p.result.status, 0) << p.result.err;
  expect_limits_where_the_blow_up_rule_puts_them(p);
  expect_euler_grows_and_symplectic_bounded(p);
}

// Found by an outputs audit: the terminal printed symplectic Euler's limit (1.9999979972839355, just
// under its strict ωh < 2) and Verlet's (2.0000000953674317, just over) both as "2" and "2.00000".
// Each limit is printed to as many figures as tell it from the theory's and from the other's.
TEST(StressPages, TheTerminalTellsTwoLimitsApartAsTheCsvDoes) {
  TempDir dir;
  const Result r = run_motus(dir, {"stress", "oscillator", "--integrators", "symplectic-euler,verlet", "--out",
                                   (dir / "s").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  std::istringstream csv(read_file(dir / "s" / "stability.csv"));
  std::string line;
  std::getline(csv, line);
  std::vector<double> limits;
  while (std::getline(csv, line)) limits.push_back(std::stod(line.substr(line.find(',') + 1)));
  ASSERT_EQ(limits.size(), 2u);
  ASSERT_GT(std::abs(limits[0] - limits[1]), 1e-6 * limits[0]) << "the two limits are apart in the CSV";
  auto printed = [&](const std::string& name) {  // the row's "largest h" field
    const size_t at = r.out.find("  " + name + " ");
    EXPECT_NE(at, std::string::npos) << r.out;
    std::istringstream row(r.out.substr(at));
    std::string integrator, h;
    row >> integrator >> h;
    return h;
  };
  EXPECT_NE(printed("symplectic-euler"), printed("verlet")) << r.out;
  char seven[32];  // seven figures: the search's bisection ends within a relative 1e-7 or so
  std::snprintf(seven, sizeof seven, "%.7g", limits[0]);
  EXPECT_EQ(printed("symplectic-euler"), seven);
}

// ---- the other pages -------------------------------------------------------------------------

// A pendulum's potential is bounded, so its energy never reached 10⁶ |E0|: steps of 15 s on a swing
// of 2 s were "stable" while it spun over the top (two audits). A swing whose energy passes its
// potential at the top, 2 m g/L, has blown up. At the bottom of the swing the pendulum is the
// oscillator of ω = √(g/L), which no step past 2/ω keeps (course.md: z < 2 for these methods).
TEST(StressPages, APendulumThatGoesOverTheTopHasBlownUp) {
  TempDir dir;
  const Result r = run_motus(dir, {"stress", "pendulum", "--integrators", "symplectic-euler,verlet,velocity-verlet",
                                   "--drift-steps", "1000", "--out", (dir / "p").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto summary = nlohmann::json::parse(read_file(dir / "p" / "summary.json"));
  ASSERT_EQ(summary.at("stability").size(), 3u);
  const double linear_limit = 2 / std::sqrt(9.81);  // the scene's g = 9.81, L = 1
  for (const auto& s : summary.at("stability")) {
    ASSERT_TRUE(s.at("limit_h").is_number()) << s.dump();
    EXPECT_GT(s.at("limit_h").get<double>(), 0) << s.dump();
    EXPECT_LT(s.at("limit_h").get<double>(), linear_limit) << s.dump();
  }
}

TEST(StressPages, KeplerPage) {
  TempDir dir;
  const Page p = make_page(dir, "kepler");
  expect_page(p, {"stability", "drift", "stiffness"});
  // Explicit Euler's orbit gains energy (integrators.md: until it escapes, which takes longer than this
  // run); RK4's error grows too; the symplectic ones stay bounded.
  std::set<std::string> judged;
  for (const auto& d : p.summary.at("drift")) {
    const std::string name = d.at("integrator"), verdict = d.at("verdict");
    if (name == "euler" || name == "rk4") {
      EXPECT_TRUE(verdict.rfind("grows", 0) == 0 || verdict.find("escaped") != std::string::npos) << d.dump();
      judged.insert(name);
    }
    if (name == "symplectic-euler" || name == "velocity-verlet" || name == "verlet") {
      EXPECT_EQ(verdict, "bounded") << d.dump();
      judged.insert(name);
    }
  }
  // (Every one of them was on the page: a missing row would leave its verdict unchecked.)
  EXPECT_EQ(judged, (std::set<std::string>{"euler", "rk4", "symplectic-euler", "velocity-verlet", "verlet"}));
}

// Found by an audit of the pictures: on the spring (ωh = √0.5 ≈ 0.71) rk4 was "bounded", beside the
// symplectic methods, while its energy drained away: its error was 0.80 in the first hundredth and
// could grow no further than 1. RK4 multiplies the oscillator's energy by |R|² = 1 − z⁶/72 + z⁸/576
// each step (z = ωh; docs/course.md §4), so after the first hundredth's 1000 steps the error is
// 1 − (|R|²)^1000, and by the last tenth the energy is gone.
TEST(StressPages, SpringPageRk4LosesItsEnergyAndSaysSo) {
  TempDir dir;
  const Page p = make_page(dir, "spring");
  ASSERT_EQ(p.result.status, 0) << p.result.err;
  const double z2 = 5.0 / 10.0 * 1.0 * 1.0;  // k/m · h², the scene's k = 5 N/m, m = 10 kg, h = 1 s
  const double factor = 1 - z2 * z2 * z2 / 72 + z2 * z2 * z2 * z2 / 576;
  std::set<std::string> judged;
  for (const auto& d : p.summary.at("drift")) {
    const std::string name = d.at("integrator"), verdict = d.at("verdict");
    if (name == "rk4") {
      EXPECT_NEAR(d.at("first_hundredth_max").get<double>(), 1 - std::pow(factor, 1000), 1e-9) << d.dump();
      EXPECT_EQ(verdict.rfind("lost its energy", 0), 0u) << d.dump();
      judged.insert(name);
    }
    if (name == "symplectic-euler" || name == "velocity-verlet" || name == "verlet" || name == "yoshida4") {
      EXPECT_EQ(verdict, "bounded") << d.dump();
      judged.insert(name);
    }
  }
  EXPECT_EQ(judged, (std::set<std::string>{"rk4", "symplectic-euler", "velocity-verlet", "verlet", "yoshida4"}));
}

TEST(StressPages, BallGasPageCollisionsExactAndNoTunnelling) {
  TempDir dir;
  const Page p = make_page(dir, "ball_gas");
  expect_page(p, {"mass_ratio", "speed"});
  long rows = 0;
  for (const auto& m : p.summary.at("mass_ratio")) {
    if (m.at("integrator") != "symplectic-euler") continue;
    ++rows;
    EXPECT_EQ(m.at("pair_failed"), "") << m.dump();
    // The course's formula (course.md, section 9), with e = 1: to rounding at every ratio.
    EXPECT_LT(m.at("pair_velocity_error").get<double>(), 1e-12) << m.dump();
    EXPECT_LT(m.at("pair_energy_error").get<double>(), 1e-12) << m.dump();
    EXPECT_LT(m.at("pair_momentum_error").get<double>(), 1e-12) << m.dump();
  }
  EXPECT_EQ(rows, 7);  // 1:1 to 1:10^6
  rows = 0;
  for (const auto& s : p.summary.at("speed")) {
    if (s.at("integrator") != "symplectic-euler") continue;
    ++rows;
    EXPECT_EQ(s.at("pair_failed"), "") << s.dump();
    EXPECT_TRUE(s.at("pair_order_kept").get<bool>()) << s.dump();  // tunnelling: never
    EXPECT_TRUE(s.at("pair_inside").get<bool>()) << s.dump();
    EXPECT_GE(s.at("pair_ball_collisions").get<long>(), 1) << s.dump();
    // The gas holds up to 100 radii per step; beyond, its 400 balls need more collisions in one
    // step than the engine allows (docs/cli.md), and the run is refused rather than wrong.
    if (s.at("radii_per_step").get<double>() <= 100) {
      EXPECT_EQ(s.at("gas_failed"), "") << s.dump();
      EXPECT_EQ(s.at("gas_outside").get<long>(), 0) << s.dump();
    } else {
      EXPECT_NE(s.at("gas_failed").get<std::string>().find("collisions in one step"), std::string::npos) << s.dump();
    }
  }
  EXPECT_EQ(rows, 5);  // 1 to 10^4 radii per step
}

TEST(StressPages, ClothPage) {
  TempDir dir;
  const Page p = make_page(dir, "cloth");
  expect_page(p, {"sticks"});
  EXPECT_EQ(p.summary.at("sticks").size(), 14u);  // two variants × seven ratios
  for (const auto& s : p.summary.at("sticks"))
    if (s.at("ratio").get<double>() == 1) {
      EXPECT_LT(s.at("max_stick_error").get<double>(), 0.01) << s.dump();  // scene-format.md: within 1 %
    }
}

// A scene that loses energy by design (a damper) has no drift section: its energy's change is
// the damper's, and every integrator, explicit Euler too, came out "bounded". Its stability and
// stiffness are measured as for any spring.
TEST(StressPages, ADampedSpringHasNoDriftSection) {
  TempDir dir;
  const Page p = make_page(dir, "damped_spring");
  expect_page(p, {"stability", "stiffness"});
  EXPECT_FALSE(fs::exists(p.folder / "drift.csv"));
  EXPECT_NE(p.summary.at("not_applied").at("drift").get<std::string>().find("loses energy by design"), std::string::npos)
      << p.summary.at("not_applied").dump();
  // (Found by an audit of the pictures: its stability figure said "energy error" of what is mostly the
  // damper's loss, where explicit Euler near its limit looked ten times more accurate than the rest.)
  const std::string gp = read_file(p.folder / "figures.gp");
  EXPECT_NE(gp.find("damped_spring: energy change of a"), std::string::npos) << gp.substr(0, 2000);
  EXPECT_EQ(gp.find("damped_spring: energy error of a"), std::string::npos);
  EXPECT_NE(gp.find("lower is not more accurate"), std::string::npos);
}

// What was not measured, or not found, says so everywhere, and the theory holds at its limit itself:
// - at dt = 0.2 the oscillator stiffened 100 times has ωh = 10 · 0.2 = 2 exactly, where the symplectic
//   methods' "ωh < 2" already fails (the run does blow up there) — the theory column said 1000;
//   RK4's "ωh ≤ 2√2" holds at 100 (2 < 2.83) and fails at 1000;
// - explicit Euler at dt = 0.5 gains 25 % of its energy a step and is no longer finite after about
//   3,200 of 5,000 steps, before the run's last tenth: summary.json had 0 for that tenth's largest
//   error, never measured;
// - free fall has no stable-step limit for midpoint: the search stops at its largest h, which the
//   terminal printed as if it were a limit.
TEST(StressPages, WhatWasNotMeasuredSaysSoAndTheTheoryHoldsAtItsLimit) {
  TempDir dir;
  const Result stiff = run_motus(dir, {"stress", "oscillator", "--set", "dt=0.2", "--steps", "1000", "--drift-steps",
                                       "100", "--integrators", "symplectic-euler,rk4", "--out", (dir / "a").string()});
  ASSERT_EQ(stiff.status, 0) << stiff.err;
  const auto a = nlohmann::json::parse(read_file(dir / "a" / "summary.json"));
  std::map<std::string, double> theory;
  for (const auto& s : a.at("stiffness").at("integrators"))
    theory[s.at("integrator").get<std::string>()] = s.at("theory_first_failure").get<double>();
  EXPECT_EQ(theory["symplectic-euler"], 100);
  EXPECT_EQ(theory["rk4"], 1000);

  const Result euler = run_motus(dir, {"stress", "oscillator", "--set", "dt=0.5", "--steps", "1000", "--drift-steps",
                                       "5000", "--integrators", "euler", "--out", (dir / "b").string()});
  ASSERT_EQ(euler.status, 0) << euler.err;
  const auto b = nlohmann::json::parse(read_file(dir / "b" / "summary.json"));
  ASSERT_EQ(b.at("drift").size(), 1u);
  EXPECT_FALSE(b.at("drift")[0].at("blown").get<std::string>().empty());
  EXPECT_TRUE(b.at("drift")[0].at("last_tenth_max").is_null()) << b.at("drift")[0].dump();
  EXPECT_TRUE(b.at("drift")[0].at("first_hundredth_max").is_number());

  // (Free fall, where this was found, now has no stability section at all: StressDrift below. An
  // oscillator of ω = 1e-6 has its limit at h = 2/ω = 2e6 s, past the search's top, dt·2²⁰ = 1e5 s.)
  const Result slow = run_motus(dir, {"stress", "oscillator", "--set", "forces[0].stiffness=1e-12", "--steps", "200",
                                      "--drift-steps", "200", "--integrators", "velocity-verlet", "--out", (dir / "c").string()});
  ASSERT_EQ(slow.status, 0) << slow.err;
  EXPECT_NE(slow.out.find("(no blow-up found: the largest h tried)"), std::string::npos) << slow.out;
}

// ---- the mass-ratio section measures collisions that happen -------------------------------------

// Found by an audit: with --duration 1 the balls of head_on, 4 m apart closing at 2 m/s, meet only at
// t = 1.5 s: every "scene" row measured a run with no collision and read 0 (verlet 4.3e-14). A row now
// runs on past --duration until --duration after the first contact, and counts its contacts. verlet's
// projected contact is perfectly inelastic (course.md, section 9, e = 0): masses 1 and 3R meeting at
// ±1 m/s keep the fraction ((1 − 3R)/(1 + 3R))² of their kinetic energy; symplectic Euler's impulses
// (e = 1) keep all of it.
TEST(StressMassRatio, TheSceneRowsMeasureContactsThatHappen) {
  TempDir dir;
  const fs::path out = dir / "page";
  const Result r = run_motus(dir, {"stress", "head_on", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  long rows = 0;
  for (const auto& m : summary.at("mass_ratio")) {
    ++rows;
    const double ratio = m.at("ratio").get<double>();
    EXPECT_EQ(m.at("gas_failed"), "") << m.dump();
    EXPECT_EQ(m.at("gas_collisions").get<long>(), 1) << m.dump();  // one head-on contact
    EXPECT_EQ(m.at("gas_steps").get<long>(), 250) << m.dump();     // contact after 150 steps of 0.01 s, then 1 s more
    const double lost = m.at("gas_max_energy_error").get<double>();
    if (m.at("integrator") == "verlet") {
      const double kept = std::pow((1 - 3 * ratio) / (1 + 3 * ratio), 2);
      EXPECT_NEAR(lost, 1 - kept, 1e-12) << m.dump();  // (rounding of E0 = 0.5 + 1.5 R over 250 steps)
    } else {
      EXPECT_LT(lost, 1e-12) << m.dump();
    }
  }
  EXPECT_EQ(rows, 14);
  const std::string csv = read_file(out / "mass_ratio.csv");
  EXPECT_NE(csv.find(",gas_steps,gas_collisions,gas_max_energy_error,gas_failed\n"), std::string::npos) << csv;
  EXPECT_NE(r.out.find("scene contacts"), std::string::npos) << r.out;
}

// Balls that never meet (head_on's, sent apart) measured no collision: the row says so, not 0.
TEST(StressMassRatio, ARunInWhichNoBallsMeetSaysSo) {
  TempDir dir;
  const fs::path out = dir / "page";
  const Result r = run_motus(dir, {"stress", "head_on", "--set", "bodies[0].velocity=[-1,0]", "--set",
                                   "bodies[1].velocity=[1,0]", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  for (const auto& m : summary.at("mass_ratio")) {
    EXPECT_EQ(m.at("gas_collisions").get<long>(), 0) << m.dump();
    EXPECT_EQ(m.at("gas_steps").get<long>(), 400) << m.dump();  // the scene's whole 4 s, looking for a contact
    EXPECT_TRUE(m.at("gas_max_energy_error").is_null()) << m.dump();
  }
  std::istringstream lines(r.out);
  std::string line;
  long said = 0;
  while (std::getline(lines, line)) said += line.find("no contact in the run") != std::string::npos;
  EXPECT_EQ(said, 14) << r.out;  // every row, both integrators
  EXPECT_NE(read_file(out / "index.html").find("no contact in the run"), std::string::npos);
}

// ---- a motion with no bound -------------------------------------------------------------------

// Found by an audit of free_fall: verlet "grows ×1.59e+08", velocity-verlet ×1.6e+06 and rk4 ×8.1e+05,
// though all three are exact for a constant force: after 1000 s its kinetic and potential energies are
// about 5e7 J each, E0 54.5 J, and |E − E0|/|E0| was cancellation. And explicit Euler's "largest stable
// step" was 10.6 s in 10⁴ steps, 33.7 s in 10³: free fall has no frequency and no stability limit.
// Explicit and symplectic Euler are not exact: each step changes the energy by exactly ± m g² h²/2
// (E_{n+1} = E_n + m v_n·g h + m g² h²/2 − m g·v_n h for explicit Euler), so after n steps by n m g² h²/2,
// which grows ×100 from the first hundredth to the end of the run.
TEST(StressDrift, FreeFallHasNoStabilityLimitAndItsRoundingIsNoDrift) {
  TempDir dir;
  const fs::path out = dir / "page";
  const Result r = run_motus(dir, {"stress", "free_fall", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_FALSE(summary.contains("stability"));
  EXPECT_FALSE(fs::exists(out / "stability.csv"));
  EXPECT_NE(summary.at("not_applied").at("stability").get<std::string>().find("no frequency"), std::string::npos);
  const double n = summary.at("settings").at("drift_steps").get<double>(), m = 1, g = 9.81, h = 0.01;  // scenes/free_fall.json
  std::set<std::string> judged;
  for (const auto& d : summary.at("drift")) {
    const std::string name = d.at("integrator"), verdict = d.at("verdict");
    if (!d.at("skipped").get<std::string>().empty()) continue;
    judged.insert(name);
    if (name == "euler" || name == "symplectic-euler" || name == "symplectic-euler-x") {
      EXPECT_EQ(verdict, "grows ×100") << d.dump();
      EXPECT_NEAR(d.at("last_tenth_max_abs").get<double>(), n * m * g * g * h * h / 2, d.at("rounding_floor").get<double>())
          << d.dump();
    } else {
      EXPECT_EQ(verdict.rfind("rounding", 0), 0u) << d.dump();
      EXPECT_LE(d.at("last_tenth_max_abs").get<double>(), d.at("rounding_floor").get<double>()) << d.dump();
    }
  }
  EXPECT_EQ(judged, (std::set<std::string>{"euler", "midpoint", "rk4", "symplectic-euler", "symplectic-euler-x", "verlet",
                                           "velocity-verlet", "yoshida4"}));
  // A drag bounds the speed, not the fall: projectile_drag's "limit" was 20.0 s in 10⁴ steps and 4.2 s
  // in 10⁵. It has no stability section either (and no drift: its drag loses energy by design).
  const Result drag = run_motus(dir, {"stress", "projectile_drag", "--out", (dir / "drag").string()});
  ASSERT_EQ(drag.status, 0) << drag.err;
  const auto d = nlohmann::json::parse(read_file(dir / "drag" / "summary.json"));
  EXPECT_TRUE(d.at("not_applied").contains("stability")) << d.dump();
  EXPECT_TRUE(d.at("sections").empty()) << d.dump();
}

// ---- failures ---------------------------------------------------------------------------------

// Found by an audit of ball_gas: a failure's message was cut mid-word to fit its cell and ran over
// three columns ("yes  more than 41000 collisions in one step: the balls …ne step, crossing many
// others: a smaller step?)"). The cell says "failed (k)", and the whole message is note k below the
// table, in every section, in the terminal and on the page.
TEST(StressTables, AFailureIsANumberedNoteBelowItsTable) {
  TempDir dir;
  const Result gas = run_motus(dir, {"stress", "ball_gas", "--integrators", "symplectic-euler", "--out", (dir / "gas").string()});
  ASSERT_EQ(gas.status, 0) << gas.err;
  std::istringstream lines(gas.out);
  std::string line;
  bool speed = false, cell = false, note = false;
  while (std::getline(lines, line)) {
    EXPECT_EQ(line.find("…"), std::string::npos) << line;  // nothing cut
    speed = speed || line.rfind("speed: ", 0) == 0;
    if (speed && line.rfind("  symplectic-euler      1000", 0) == 0) {
      cell = true;
      EXPECT_EQ(line.substr(line.size() - 10), "failed (1)") << line;
    }
    if (line.rfind("  (1) more than 41000 collisions in one step: ", 0) == 0) note = line.back() == ')';
  }
  EXPECT_TRUE(cell && note) << gas.out;
  const std::string html = read_file(dir / "gas" / "index.html");
  EXPECT_NE(html.find(">failed (1)</td>"), std::string::npos);
  EXPECT_NE(html.find("<p class=\"no\">(1) more than 41000 collisions in one step: "), std::string::npos);
  // The mass-ratio table the same way: newtons_cradle's 1:10⁶ contact is an inelastic collapse.
  const Result cradle = run_motus(dir, {"stress", "newtons_cradle", "--integrators", "symplectic-euler", "--out",
                                        (dir / "cradle").string()});
  ASSERT_EQ(cradle.status, 0) << cradle.err;
  EXPECT_NE(cradle.out.find("     1e+06"), std::string::npos) << cradle.out;
  EXPECT_NE(cradle.out.find("  failed (1)\n  (1) more than 1500 collisions in one step: "), std::string::npos) << cradle.out;
  EXPECT_NE(read_file(dir / "cradle" / "index.html").find("(1) more than 1500 collisions in one step: "), std::string::npos);
}

// ---- what does not apply ----------------------------------------------------------------------

// Found by an audit: drop (one body) gave the same "scene" mass-ratio error, 0.000467, at every ratio
// (there is no second body to be heavier) and "no body moves" as a speed failure; stick_pendulum's 14
// sticks rows were all 2.2e-16, its two variants the same bob, whose stick ends at a pinned pivot; and
// head_on, with no container, had "in box yes / outside 0". Each is listed as not measured, with why.
TEST(StressNotMeasured, RowsThatWouldMeasureNothingAreListedWithWhy) {
  TempDir dir;
  const Result drop = run_motus(dir, {"stress", "drop", "--out", (dir / "drop").string()});
  ASSERT_EQ(drop.status, 0) << drop.err;
  const auto a = nlohmann::json::parse(read_file(dir / "drop" / "summary.json"));
  EXPECT_NE(a.at("not_applied").at("mass_ratio (the scene)").get<std::string>().find("one body"), std::string::npos);
  EXPECT_NE(a.at("not_applied").at("speed (the scene)").get<std::string>().find("no body moves"), std::string::npos);
  for (const auto& m : a.at("mass_ratio")) {
    EXPECT_FALSE(m.at("gas_measured").get<bool>()) << m.dump();
    EXPECT_TRUE(m.at("gas_max_energy_error").is_null()) << m.dump();
    EXPECT_EQ(m.at("pair_failed"), "") << m.dump();  // (the pair is two balls of its own: still measured)
  }
  for (const auto& s : a.at("speed")) EXPECT_EQ(s.at("gas_failed"), "") << s.dump();
  EXPECT_EQ(drop.out.find("scene |dE|/E0"), std::string::npos) << drop.out;
  const size_t moves = drop.out.find("no body moves");  // once, as the reason, and never as a row's failure
  EXPECT_NE(drop.out.find("not measured: speed (the scene): no body moves at the start"), std::string::npos) << drop.out;
  ASSERT_NE(moves, std::string::npos);
  EXPECT_EQ(drop.out.find("no body moves", moves + 1), std::string::npos) << drop.out;

  const Result pendulum = run_motus(dir, {"stress", "stick_pendulum", "--out", (dir / "pendulum").string()});
  ASSERT_EQ(pendulum.status, 0) << pendulum.err;
  const auto b = nlohmann::json::parse(read_file(dir / "pendulum" / "summary.json"));
  EXPECT_TRUE(b.at("sections").empty()) << b.dump();
  const std::string why = b.at("not_applied").at("sticks").get<std::string>();
  EXPECT_NE(why.find("pinned"), std::string::npos) << why;
  EXPECT_NE(why.find("the same free bodies"), std::string::npos) << why;
  EXPECT_FALSE(fs::exists(dir / "pendulum" / "sticks.csv"));
  EXPECT_NE(pendulum.out.find("sections: none"), std::string::npos) << pendulum.out;

  const Result head_on = run_motus(dir, {"stress", "head_on", "--out", (dir / "head_on").string()});
  ASSERT_EQ(head_on.status, 0) << head_on.err;
  const auto c = nlohmann::json::parse(read_file(dir / "head_on" / "summary.json"));
  EXPECT_NE(c.at("not_applied").at("speed (balls outside their container)").get<std::string>().find("no container"),
            std::string::npos);
  for (const auto& s : c.at("speed")) EXPECT_TRUE(s.at("gas_outside").is_null()) << s.dump();
  EXPECT_EQ(head_on.out.find("outside"), head_on.out.find("outside their container")) << head_on.out;
  EXPECT_EQ(read_file(dir / "head_on" / "index.html").find("scene: outside"), std::string::npos);
}

// Found by fuzzing the options: a --duration longer than the scene's was cut to the scene's without
// a word (summary.json said 4 s where 1000 was asked). The runs still take at most the scene's, and
// the terminal says so.
TEST(StressPages, ADurationLongerThanTheScenesIsSaid) {
  TempDir dir;
  const fs::path out = dir / "page";
  const Result r = run_motus(dir, {"stress", "head_on", "--duration", "1000", "--steps", "100", "--integrators",
                                   "symplectic-euler", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("--duration 1000 s is more than the scene's 4 s: its runs took 4 s"), std::string::npos) << r.out;
  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  EXPECT_EQ(summary.at("settings").at("duration").get<double>(), 4.0) << summary.dump();
}

// ---- bad input -------------------------------------------------------------------------------

TEST(StressErrors, BadInputIsOneLineAndExitTwo) {
  TempDir dir;
  const std::vector<std::vector<std::string>> cases = {
      {"stress", "lorenz", "--out", (dir / "a").string()},
      {"stress", "oscillator", "--integrators", "rk5", "--out", (dir / "b").string()},
      {"stress", "oscillator", "--integrators", "euler,", "--out", (dir / "e").string()},  // an empty name
      {"stress", "oscillator", "--energy-factor", "0.5", "--out", (dir / "c").string()},
      {"stress", "oscillator", "--out", dir.path().string()},  // exists
      {"stress", "oscillator", "--steps", "10"},
      {"stress", "ball_gas", "--integrators", "rk4", "--out", (dir / "d").string()},
      // (adaptive methods only: every section said "adaptive: it chooses its own steps", exit 0)
      {"stress", "oscillator", "--integrators", "rk45", "--out", (dir / "g").string()},
      // (at t = 1e17 times are 16 apart: steps of 0.1 never moved the clock, and stress hung)
      {"stress", "oscillator", "--set", "start_time=1e17", "--integrators", "verlet", "--out", (dir / "f").string()},
      // (a duration shorter than a step: its mass-ratio runs took none, exit 0; found by fuzzing)
      {"stress", "head_on", "--duration", "1e-300", "--out", (dir / "h").string()},
  };
  for (const auto& args : cases) {
    const Result r = run_motus(dir, args);
    EXPECT_EQ(r.status, 2) << args[1] << " " << (args.size() > 2 ? args[2] : "") << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("motus: error: ", 0), 0u) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "a"));
  EXPECT_FALSE(fs::exists(dir / "d"));
  EXPECT_FALSE(fs::exists(dir / "e"));
  EXPECT_FALSE(fs::exists(dir / "g"));
}

// Ctrl-C while the page is being drawn (a stand-in gnuplot that waits): exit 130, and no folder,
// neither the page nor its partial one (cli/output_files.hpp, PartialFolder).
TEST(StressErrors, AnInterruptedStressExits130AndLeavesNoFolder) {
  TempDir dir;
  const fs::path out = dir / "page";
  const Result r = interrupt_motus_while_plotting(
      dir, {"stress", "oscillator", "--out", out.string(), "--steps", "1000", "--drift-steps", "1000"});
  EXPECT_EQ(r.status, 130) << r.err;
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_TRUE(e.path().filename() == "bin" || e.path().filename() == "stdout.txt" ||
                e.path().filename() == "stderr.txt")
        << "left behind: " << e.path();
}

// Found by an accessibility audit: no <html lang> or viewport, tables without named headers, and
// numbers without units ("largest stable h", "dt = 0.1;", "not finite at t = 7134"), and "1 body in
// 1 dimensions".
TEST(Stress, ThePageIsNamedItsTablesHaveHeadersAndItsNumbersUnits) {
  TempDir dir;
  Page p;  // (explicit Euler at dt = 0.5 blows up within its long run)
  p.folder = dir / "oscillator";
  p.result = run_motus(dir, {"stress", "oscillator", "--set", "dt=0.5", "--steps", "1000", "--drift-steps", "5000",
                             "--integrators", "euler", "--out", p.folder.string()});
  ASSERT_EQ(p.result.status, 0) << p.result.err;
  p.summary = nlohmann::json::parse(read_file(p.folder / "summary.json"));
  const std::string html = read_file(p.folder / "index.html");
  EXPECT_TRUE(starts_as_a_page(html));
  EXPECT_TRUE(tables_have_headers(html));
  EXPECT_NE(html.find("<th scope=\"col\">largest stable h [s]</th>"), std::string::npos);
  const double dt = p.summary.at("dt").get<double>();
  std::ostringstream steps;
  steps << "steps of the scene's dt = " << dt << " s;";
  EXPECT_NE(html.find(steps.str()), std::string::npos) << steps.str();
  EXPECT_NE(html.find("<p>1 body in 1 dimension, "), std::string::npos);
  // Explicit Euler's long run blows up: when, in seconds.
  bool blown = false;
  for (const auto& d : p.summary.at("drift"))
    if (!d.at("blown").get<std::string>().empty()) {
      blown = true;
      EXPECT_TRUE(std::regex_search(d.at("blown").get<std::string>(), std::regex(R"( at t = [0-9.e+]+ s$)"))) << d;
    }
  EXPECT_TRUE(blown) << p.summary.at("drift");
}

}  // namespace

namespace {

// Each line's colour (and dash) in a figures.gp, by its legend's title: "lc rgb '#9164c8' dt (24,6,3,6)".
std::map<std::string, std::set<std::string>> line_styles(const std::string& script) {
  std::map<std::string, std::set<std::string>> styles;
  const std::regex line(R"((lc rgb '#[0-9a-f]{6}'(?: dt [^ ]+)?) title '([^']*)')");
  for (auto it = std::sregex_iterator(script.begin(), script.end(), line); it != std::sregex_iterator(); ++it)
    styles[(*it)[2].str()].insert((*it)[1].str());
  return styles;
}

}  // namespace

// A pictures audit: the stress page coloured its methods by their order in each figure, bench precision
// by their place in motus's table, so rk4 was purple on one page and orange on the other. Both now take the
// method's colour (plot::integrator_colour): one colour a method, in every figure of both pages.
TEST(StressPages, AMethodHasTheColourItHasInBenchPrecision) {
  TempDir dir;
  const Result stress = run_motus(dir, {"stress", "oscillator", "--integrators", "rk4,euler", "--steps", "100",
                                        "--drift-steps", "100", "--out", (dir / "stress").string()});
  ASSERT_EQ(stress.status, 0) << stress.err;
  const Result bench = run_motus(dir, {"bench", "precision", "oscillator", "--integrators", "euler,rk4", "--levels", "1",
                                       "--per-decade", "1", "--repeats", "1", "--out", (dir / "bench").string()});
  ASSERT_EQ(bench.status, 0) << bench.err;
  const auto in_stress = line_styles(read_file(dir / "stress" / "figures.gp"));
  const auto in_bench = line_styles(read_file(dir / "bench" / "figures.gp"));
  for (const char* method : {"euler", "rk4"}) {
    ASSERT_TRUE(in_stress.contains(method) && in_bench.contains(method)) << method;
    EXPECT_EQ(in_stress.at(method).size(), 1u) << method << ": more than one style on the stress page";
    EXPECT_EQ(in_stress.at(method), in_bench.at(method)) << method;
  }
  EXPECT_NE(in_stress.at("euler"), in_stress.at("rk4"));
}
