// `motus compare` as a user runs it (docs/cli.md): the side-by-side table, the --json
// summary, the report folder, "not supported" for what a peer cannot run, and a report
// never written over an existing folder. The peers' numbers themselves are held in
// test_compare_box2d.cpp and test_compare_bullet.cpp (sources: tests/reference/peers.md).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

#include "cli_harness.hpp"

namespace {

using namespace motus_test;

const nlohmann::json* engine(const nlohmann::json& summary, const std::string& name) {
  for (const auto& e : summary.at("engines"))
    if (e.at("engine") == name) return &e;
  return nullptr;
}

TEST(Compare, HeadOnInThreeEnginesWritesTheReport) {
  TempDir dir;
  const fs::path out = dir / "report";
  const Result r = run_motus(dir, {"compare", scene("head_on"), "--out", out.string(), "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("scene"), "head_on");
  EXPECT_EQ(j.at("report"), (out / "index.html").string());
  for (const char* name : {"motus", "box2d", "bullet"}) {
    const auto* e = engine(j, name);
    ASSERT_NE(e, nullptr) << name;
    ASSERT_TRUE(e->at("supported").get<bool>()) << name << ": " << e->at("unsupported").dump();
    EXPECT_EQ(e->at("steps"), 400) << name;  // 4 s at dt = 0.01 (scenes/head_on.json)
    for (const char* field : {"energy_drift", "momentum_drift", "max_penetration", "constraint_error", "us_per_step"})
      EXPECT_TRUE(e->at(field).is_number()) << name << "." << field;
    EXPECT_FALSE(e->at("settings").empty()) << name;
  }
  // motus against itself: no distance, and the time ratio 1.
  EXPECT_EQ(engine(j, "motus")->at("max_distance_from_motus"), 0.0);
  EXPECT_EQ(engine(j, "motus")->at("time_relative_to_motus"), 1.0);
  // e = 1 head-on: momentum kept by all three (tests/reference/peers.md: both peers give the exact result).
  for (const char* name : {"motus", "box2d", "bullet"}) EXPECT_LT(engine(j, name)->at("momentum_drift").get<double>(), 1e-6) << name;
  for (const char* file : {"index.html", "metrics.csv", "summary.json", "figures.gp", "energy.svg", "energy.png"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  const std::string html = read_file(out / "index.html");
  EXPECT_NE(html.find("<table>"), std::string::npos);
  EXPECT_NE(html.find("box2d"), std::string::npos);
  // metrics.csv: a header and 201 samples per engine (t0 and 200 more: the default --samples).
  const std::string csv = read_file(out / "metrics.csv");
  EXPECT_EQ(count_lines(csv), 1 + 3 * 201);
}

// The deepest overlap is taken every step, not at the samples: an engine that resolves a contact
// after it happens overlaps for a step or two, between samples (Box2D's head_on read 0 at the
// default 200 samples and 1.6e-4 m at 400; an audit). So the column no longer depends on --samples.
TEST(Compare, TheDeepestOverlapIsTakenEveryStepWhateverTheSamples) {
  TempDir dir;
  std::map<std::string, double> deepest;
  for (const char* samples : {"10", "400"}) {
    const Result r = run_motus(dir, {"compare", scene("head_on"), "--engines", "motus,box2d", "--samples", samples,
                                     "--out", (dir / samples).string(), "--json", "--repeats", "1"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(engine(j, "motus")->at("max_penetration").get<double>(), 0) << samples;  // exact collisions
    deepest[samples] = engine(j, "box2d")->at("max_penetration").get<double>();
  }
  // How deep: head_on's balls (radius 0.5 at x = ∓2, ±1 m/s, dt = 0.01 s) close 2 cm a step and touch
  // after exactly 150 steps; Box2D finds a contact only once the circles overlap, and float's rounding
  // leaves them a hair apart then, so the next step carries them a whole step into each other:
  // closing speed × dt = 2 m/s × 0.01 s = 0.02 m, less that hair. The hair is the rounding of 150
  // float steps x += h·v for each ball, at most half an ulp of |x| ≤ 2 m a step: 150 × 2 × 2⁻²³ m
  // (half of float's 2⁻²² at 2 m) = 3.6e-5 m, bound. Measured: 0.0199971 m (a 2.9e-6 m hair).
  EXPECT_NEAR(deepest["400"], 2 * 0.01, 150 * 2 * 0x1p-23);
  EXPECT_LE(deepest["400"], 2 * 0.01);  // (the hair is a gap, not an overlap: else the contact came a step sooner)
  EXPECT_EQ(deepest["10"], deepest["400"]);
}

TEST(Compare, RepeatsAreTimingRoundsSummarizedByTheirMinimumAndMedian) {
  // --repeats 3: every engine's three rounds are in the JSON, and the time per step is their
  // minimum, with the median and the spread (max − min)/min beside it (docs/cli.md).
  TempDir dir;
  const Result r = run_motus(dir, {"compare", scene("head_on"), "--out", (dir / "r").string(), "--json", "--repeats", "3"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("repeats"), 3);
  for (const char* name : {"motus", "box2d", "bullet"}) {
    const auto& e = *engine(j, name);
    std::vector<double> rounds = e.at("us_per_step_rounds").get<std::vector<double>>();
    ASSERT_EQ(rounds.size(), 3u) << name;
    std::sort(rounds.begin(), rounds.end());
    EXPECT_EQ(e.at("us_per_step").get<double>(), rounds[0]) << name;
    EXPECT_EQ(e.at("us_per_step_median").get<double>(), rounds[1]) << name;
    EXPECT_EQ(e.at("us_per_step_max").get<double>(), rounds[2]) << name;
    EXPECT_DOUBLE_EQ(e.at("us_per_step_spread").get<double>(), (rounds[2] - rounds[0]) / rounds[0]) << name;
  }
  // Without --repeats a scene this small gets the five rounds (the default: as many as fit in 3 s).
  const Result d = run_motus(dir, {"compare", scene("head_on"), "--out", (dir / "d").string(), "--json"});
  ASSERT_EQ(d.status, 0) << d.err;
  EXPECT_EQ(nlohmann::json::parse(d.out).at("repeats"), 5);
  // One round has no spread: null (the table's –), not 0 %, which read as perfectly steady timings.
  const Result one = run_motus(dir, {"compare", scene("head_on"), "--out", (dir / "one").string(), "--json", "--repeats", "1"});
  ASSERT_EQ(one.status, 0) << one.err;
  for (const char* name : {"motus", "box2d", "bullet"})
    EXPECT_TRUE(engine(nlohmann::json::parse(one.out), name)->at("us_per_step_spread").is_null()) << name;
}

TEST(Compare, OnTheStickScenesMotusKeepsItsSticksAtLeastAsWellAsBothPeers) {
  // Issue 13: on cloth, rope, ragdoll and stick_pendulum, motus's largest stick error is at most
  // each peer's, measured in the same run by the same metrics code, which takes the stick error
  // after every step whatever --samples says (comparison.cpp: the error every step of a scene with
  // sticks), so the default samples do.
  for (const char* name : {"cloth", "rope", "ragdoll", "stick_pendulum"}) {
    TempDir dir;
    const Result r = run_motus(dir, {"compare", scene(name), "--out", (dir / "r").string(), "--json", "--repeats", "1"});
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const double mine = engine(j, "motus")->at("constraint_error").get<double>();
    std::printf("  %s: largest stick error motus %.2e", name, mine);
    for (const char* peer : {"box2d", "bullet"}) {
      const auto& e = *engine(j, peer);
      if (!e.at("supported").get<bool>()) continue;  // (Box2D: the 3-D cloth)
      const double theirs = e.at("constraint_error").get<double>();
      std::printf(", %s %.2e", peer, theirs);
      EXPECT_LE(mine, theirs) << name << " against " << peer;
    }
    std::printf("\n");
  }
}

// A stick written 1 m long between bodies 0.943 m apart: the start's 5.7 % is the scene's, and it
// was every engine's figure alike (motus 0.057, box2d 0.057, bullet 0.057: an audit). The figures
// now begin after the first step (motus's projection keeps the stick to rounding, Box2D's joint
// to ~1e-7), and the sentence names the start's mismatch once.
TEST(Compare, ASceneWhoseSticksStartOffTheirLengthsChargesNoEngineWithIt) {
  TempDir dir;
  write_file(dir / "off.json", R"({"name": "off", "dimensions": 2,
    "bodies": [{"mass": 1, "position": [0, 0]}, {"mass": 1, "position": [0.943, 0], "velocity": [0, 1]}],
    "sticks": [{"a": 0, "b": 1, "length": 1}], "integrator": "verlet", "dt": 0.01, "duration": 1})");
  const Result r = run_motus(dir, {"compare", (dir / "off.json").string(), "--out", (dir / "r").string(), "--json",
                                   "--repeats", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(engine(j, "motus")->at("constraint_error").get<double>(), 1e-12);
  EXPECT_LT(engine(j, "box2d")->at("constraint_error").get<double>(), 1e-4);
  EXPECT_NE(j.at("notice").get<std::string>().find("the scene starts with them off by up to 0.057 (its own lengths against "
                                                   "its positions, not counted)"),
            std::string::npos)
      << j.at("notice");
  // A scene that starts on its lengths says nothing of it.
  const Result rope = run_motus(dir, {"compare", scene("rope"), "--out", (dir / "rope").string(), "--json", "--repeats", "1"});
  ASSERT_EQ(rope.status, 0) << rope.err;
  EXPECT_EQ(nlohmann::json::parse(rope.out).at("notice").get<std::string>().find("starts with them off"), std::string::npos);
}

TEST(Compare, ABox2dCannotRunA3dSceneAndSaysSo) {
  TempDir dir;
  const Result r = run_motus(dir, {"compare", scene("bouncing_balls_3d"), "--engines", "motus,box2d", "--duration", "0.1",
                                   "--out", (dir / "r").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("not supported by box2d: 3-D scenes"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(read_file(dir / "r" / "summary.json"));
  EXPECT_FALSE(engine(j, "box2d")->at("supported").get<bool>());
  EXPECT_EQ(engine(j, "box2d")->at("unsupported")[0], "not supported by box2d: 3-D scenes");
  EXPECT_TRUE(engine(j, "motus")->at("supported").get<bool>());
}

// Explicit Euler at h = 0.5 s on the 1 s spring grows by √(1 + (ωh)²) a step: by t = 2000 the
// momentum is −5.7e193 kg·m/s, a finite number whose square is not. The scene starts at rest
// (p₀ = 0), so the momentum column is the change in kg·m/s, |p − p₀| = |p| — in the summary and
// in metrics.csv's every row, not ∞ or "-" from the square's overflow.
TEST(Compare, AMomentumPastTheSquareRootOfTheLargestDoubleIsStillItsSize) {
  TempDir dir;
  const Result r = run_motus(dir, {"compare", scene("oscillator"), "--engines", "motus", "--integrator", "euler", "--dt",
                                   "0.5", "--duration", "2000", "--repeats", "1", "--out", (dir / "r").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(read_file(dir / "r" / "summary.json"));
  const auto& motus = *engine(j, "motus");
  const double p = motus.at("momentum").at("final")[0].get<double>();
  ASSERT_GT(std::abs(p), 1e190);
  ASSERT_TRUE(motus.at("momentum_drift").is_number()) << motus.dump();
  EXPECT_DOUBLE_EQ(motus.at("momentum_drift").get<double>(), std::abs(p));
  for (const auto& row : csv_data_rows(read_file(dir / "r" / "metrics.csv"))) {
    const double px = std::stod(row.at(7)), change = std::stod(row.at(6));
    if (std::isfinite(px)) {
      EXPECT_NEAR(change, std::abs(px), 1e-6 * std::abs(px)) << "t = " << row.at(1);
    }
  }
}

TEST(Compare, NeverWritesOverAnExistingFolder) {
  TempDir dir;
  fs::create_directories(dir / "taken");
  write_file(dir / "taken" / "keep.txt", "mine");
  const Result r = run_motus(dir, {"compare", scene("head_on"), "--out", (dir / "taken").string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("already exists"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(dir / "taken" / "keep.txt"), "mine");
}

// A PNG's width and height, from its IHDR chunk (bytes 16–23, big-endian).
std::pair<unsigned, unsigned> png_size(const fs::path& file) {
  const std::string bytes = read_file(file);
  auto word = [&](size_t at) {
    unsigned v = 0;
    for (size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes.at(at + k));
    return v;
  };
  return {word(16), word(20)};
}

TEST(Compare, RenderDrawsTheEnginesSideBySideIntoTheReport) {
  // 1 s of head_on at 5 frames per second: frames at t = 0, 0.2, ..., 1.0 — six of them,
  // each three panels of 160 × 120 side by side (wider than three panels: labels and gaps).
  TempDir dir;
  const fs::path out = dir / "r";
  const Result r = run_motus(dir, {"compare", scene("head_on"), "--render", "--size", "160x120", "--fps", "5",
                                   "--duration", "1", "--out", out.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  long frames = 0;
  for (const auto& f : fs::directory_iterator(out / "frames")) frames += f.path().extension() == ".png";
  EXPECT_EQ(frames, 6);
  const auto [width, height] = png_size(out / "frames" / "frame_00000.png");
  EXPECT_GE(width, 3u * 160);
  EXPECT_LT(width, 3u * 160 + 40);
  EXPECT_GE(height, 120u);
  ASSERT_TRUE(fs::exists(out / "contact_sheet.png"));
  const std::string html = read_file(out / "index.html");
  EXPECT_NE(html.find("contact_sheet.png"), std::string::npos);
  // The first and the last instant are in every report, --render or not (docs/cli.md).
  EXPECT_TRUE(fs::exists(out / "first_and_last.png"));
  EXPECT_NE(html.find("<img src=\"first_and_last.png\""), std::string::npos);
  // The video needs ffmpeg, looked for on PATH: without it the run says so and makes none, and the
  // rest is not checked here (as the render tests skip).
  if (r.err.find("ffmpeg not found on PATH") != std::string::npos) GTEST_SKIP() << "no ffmpeg here: " << r.err;
  EXPECT_TRUE(fs::exists(out / "comparison.mp4")) << r.err;
  EXPECT_NE(html.find("<video src=\"comparison.mp4\""), std::string::npos);
  // A % in the folder is no part of ffmpeg's frame pattern (the video failed, and the report
  // showed none of the pictures).
  const fs::path percent = dir / "c_50%";
  const Result p = run_motus(dir, {"compare", scene("head_on"), "--render", "--size", "64x48", "--fps", "5",
                                   "--duration", "0.4", "--engines", "motus", "--out", percent.string()});
  ASSERT_EQ(p.status, 0) << p.err;
  EXPECT_TRUE(fs::exists(percent / "comparison.mp4")) << p.err;
  EXPECT_NE(read_file(percent / "index.html").find("first_and_last.png"), std::string::npos);
}

TEST(Compare, AReportFolderNamedWithATrailingSlashIsThatFolder) {
  // "--out r/" is the folder r: the report is written there, not lost inside it.
  TempDir dir;
  const Result r = run_motus(dir, {"compare", scene("head_on"), "--engines", "motus", "--duration", "0.1", "--out",
                                   (dir / "r").string() + "/", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "r" / "index.html"));
  EXPECT_TRUE(fs::exists(dir / "r" / "summary.json"));
  for (const auto& f : fs::directory_iterator(dir.path()))  // (no .r.partial-* folder left behind)
    EXPECT_NE(f.path().filename().string().front(), '.') << "left behind: " << f.path();
}

TEST(Compare, PenetrationCountsSegmentsAsItCountsPlanes) {
  // A ball of radius 0.5 whose centre starts 0.2 m from a wall is 0.3 m into it at t = 0,
  // whether the wall is a plane or a segment (docs/cli.md: ball–ball and ball–wall overlap).
  TempDir dir;
  const std::string ball =
      R"("dimensions": 2, "integrator": "symplectic-euler", "bodies": [{"mass": 1, "radius": 0.5, "position": [0, 0.2]}],)";
  const std::string run = R"("dt": 0.01, "duration": 0.05})";
  write_file(dir / "plane.json",
             R"({"name": "plane", )" + ball + R"("colliders": [{"type": "plane", "normal": [0, 1], "offset": 0}], )" + run);
  write_file(dir / "segment.json",
             R"({"name": "segment", )" + ball + R"("colliders": [{"type": "segment", "a": [-5, 0], "b": [5, 0]}], )" + run);
  for (const char* wall : {"plane", "segment"}) {
    const Result r = run_motus(dir, {"compare", (dir / (std::string(wall) + ".json")).string(), "--engines", "motus",
                                     "--out", (dir / (std::string(wall) + "_report")).string(), "--json"});
    ASSERT_EQ(r.status, 0) << wall << ": " << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_NEAR(engine(j, "motus")->at("max_penetration").get<double>(), 0.3, 1e-12) << wall;
  }
}

TEST(Compare, AScenesStartingWithNoEnergyHasItsEnergyColumnsInJoules) {
  // stick_pendulum is let go at rest from its pivot's height: E₀ = 0, and (E − E₀)/|E₀| would be
  // no number. The columns are then in joules, and say so; head_on's (E₀ = 2 J) are fractions.
  TempDir dir;
  const Result pendulum = run_motus(dir, {"compare", scene("stick_pendulum"), "--engines", "motus", "--out",
                                          (dir / "p").string(), "--json", "--duration", "1"});
  ASSERT_EQ(pendulum.status, 0) << pendulum.err;
  const auto j = nlohmann::json::parse(pendulum.out);
  EXPECT_EQ(j.at("energy_unit"), "J");
  // The last sample's energy, in joules, is the drift: E_end − 0.
  const auto rows = csv_data_rows(read_file(dir / "p" / "metrics.csv"));
  EXPECT_DOUBLE_EQ(engine(j, "motus")->at("energy_drift").get<double>(), std::stod(rows.back().at(4)));
  EXPECT_NE(j.at("definitions").dump().find("energy drift [J]"), std::string::npos);
  EXPECT_NE(read_file(dir / "p" / "index.html").find("<th scope=\"col\">energy drift [J]</th>"), std::string::npos);
  EXPECT_NE(read_file(dir / "p" / "figures.gp").find("E0| [J]"), std::string::npos);
  const Result table = run_motus(dir, {"compare", scene("stick_pendulum"), "--engines", "motus", "--out",
                                       (dir / "t").string(), "--duration", "1"});
  EXPECT_NE(table.out.find("max |dE| [J]"), std::string::npos) << table.out;
  const Result head_on = run_motus(dir, {"compare", scene("head_on"), "--engines", "motus", "--out",
                                         (dir / "h").string(), "--json", "--duration", "0.1"});
  ASSERT_EQ(head_on.status, 0) << head_on.err;
  EXPECT_EQ(nlohmann::json::parse(head_on.out).at("energy_unit"), "E0");
  // So is the momentum: nothing moves at the start, so there is no scale, and its column is the
  // change itself, in kg·m/s, and says so; head_on's is a fraction of the momentum in play.
  EXPECT_EQ(j.at("momentum_unit"), "kg·m/s");
  EXPECT_NE(table.out.find("p [kg m/s]"), std::string::npos) << table.out;
  EXPECT_NE(read_file(dir / "p" / "index.html").find("<th scope=\"col\">momentum drift [kg·m/s]"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(head_on.out).at("momentum_unit"), "scale");
}

// Every engine's energy columns are in the one unit the scene's start decides (motus's E₀), and
// each is that engine's own change in it. This ball starts where its energy is exactly 0 in doubles
// (½·1·0.1² = 0.005 of motion, −1·1·0.005 of height) but not in Box2D's floats (2.6e-10 J): Box2D's
// column, in joules, was its change divided by those 2.6e-10 J (−1.9e7, the same in metrics.csv
// and the energy figure).
TEST(Compare, EveryEnginesEnergyColumnIsInTheUnitTheTableSays) {
  TempDir dir;
  write_file(dir / "e0.json", R"({"name": "e0", "dimensions": 2, "bodies": [{"mass": 1, "radius": 0.01,
    "position": [0, -0.005000000000000001], "velocity": [0.1, 0]}], "forces": [{"type": "gravity", "g": [0, -1]}],
    "integrator": "symplectic-euler", "dt": 0.01, "duration": 1})");
  const Result r = run_motus(dir, {"compare", (dir / "e0.json").string(), "--engines", "motus,box2d", "--out",
                                   (dir / "r").string(), "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.at("energy_unit"), "J");
  // Symplectic Euler under constant g, from rest vertically: v_n = −g n h, y_n = y₀ − g h² n(n + 1)/2,
  // so E_n − E₀ = ½ g² n² h² − g² h² n(n + 1)/2 = −g² h t / 2 = −0.005 J at t = 1 (g = 1, h = 0.01);
  // Box2D steps the same way, to its floats' rounding.
  const double motus = engine(j, "motus")->at("energy_drift").get<double>();
  const double box2d = engine(j, "box2d")->at("energy_drift").get<double>();
  EXPECT_NEAR(motus, -0.005, 1e-12);  // (doubles: rounding in 100 steps' energies of ~0.01 J, ~1e-17 each)
  EXPECT_NEAR(box2d, motus, 1e-5) << "box2d's column is not in joules";
  EXPECT_NEAR(engine(j, "box2d")->at("max_energy_error").get<double>(), std::abs(motus), 1e-5);
  std::vector<std::string> last;  // box2d's last row of metrics.csv: its energy_error, in joules too
  for (const auto& row : csv_data_rows(read_file(dir / "r" / "metrics.csv")))
    if (row.at(0) == "box2d") last = row;
  ASSERT_FALSE(last.empty());
  EXPECT_NEAR(std::stod(last.at(5)), box2d, 1e-6);
}

// A long run steps motus exactly as many times as the peers: compare's motus column advances to
// t0 + k·dt one step at a time, and took two steps at once after ~17,000 (simulation.hpp's clock).
TEST(Compare, ALongRunEndsMotusAtItsLastStepsTime) {
  TempDir dir;
  const Result r = run_motus(dir, {"compare", scene("head_on"), "--engines", "motus", "--dt", "0.01", "--duration",
                                   "200", "--samples", "4", "--repeats", "1", "--out", (dir / "r").string(), "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(engine(nlohmann::json::parse(r.out), "motus")->at("steps").get<long>(), 20000);
  const auto rows = csv_data_rows(read_file(dir / "r" / "metrics.csv"));
  ASSERT_FALSE(rows.empty());
  EXPECT_EQ(std::stod(rows.back().at(1)), 200.0) << rows.back().at(1);  // (it ended at 200.01)
}

// The report's time per step is the table's: Bullet's 2,734 µs per step on 2,000 balls read
// 2.73e+03 in index.html.
TEST(Compare, TheReportShowsEachTimePerStepAsTheTableDoes) {
  TempDir dir;
  const Result r = run_motus(dir, {"compare", scene("ball_gas"), "--set", "lattice.count=2000", "--duration", "0.1",
                                   "--engines", "motus,bullet", "--repeats", "1", "--out", (dir / "r").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string html = read_file(dir / "r" / "index.html");
  int rows = 0;
  std::istringstream table(r.out);
  for (std::string line; std::getline(table, line);) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.size() != 11 || (w[0] != "motus" && w[0] != "bullet")) continue;
    ++rows;
    for (const std::string& time : {w[7], w[8]})  // us/step and its median
      EXPECT_NE(html.find("<td>" + time + "</td>"), std::string::npos) << w[0] << ": " << time << " not in the report";
  }
  EXPECT_EQ(rows, 2) << r.out;
}

// A pendulum's coordinate is its angle (scene-format.md, Units): its distance from the exact
// answer is in radians, as the closing sentence says (it said metres).
TEST(Compare, APendulumsDistanceFromTheExactAnswerIsInRadians) {
  TempDir dir;
  const Result r = run_motus(dir, {"compare", scene("pendulum"), "--engines", "motus", "--repeats", "1", "--duration", "1",
                                   "--out", (dir / "p").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("strays over the run: motus "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" rad."), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(" m."), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("pendulum: 1 body, 1-D"), std::string::npos) << r.out;  // (not "1 bodies")
  const std::string page = read_file(dir / "p" / "index.html");
  EXPECT_NE(page.find("1 body in 1 dimension;"), std::string::npos);
  EXPECT_NE(page.find("over one timing round."), std::string::npos);
}

TEST(Compare, MetricsCsvAgreesWithTheSummary) {
  // --samples 300 over head_on's 400 steps: 300 samples and the start (it took 400, one every
  // floor(400/300) = 1 step); the momentum change of the last row is the summary's momentum drift
  // (stick_pendulum starts at rest: the CSV divided it by 1e-300); with no motus run, the distance
  // from motus is an empty cell, not 0.
  TempDir dir;
  Result r = run_motus(dir, {"compare", scene("head_on"), "--engines", "motus", "--samples", "300", "--out",
                             (dir / "s").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(csv_data_rows(read_file(dir / "s" / "metrics.csv")).size(), 301u);

  r = run_motus(dir, {"compare", scene("stick_pendulum"), "--engines", "motus,box2d", "--out", (dir / "p").string(),
                      "--json", "--duration", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto rows = csv_data_rows(read_file(dir / "p" / "metrics.csv"));
  for (const char* name : {"motus", "box2d"}) {
    std::vector<std::string> last;
    for (const auto& row : rows)
      if (row.at(0) == name) last = row;
    ASSERT_FALSE(last.empty()) << name;
    const double drift = engine(j, name)->at("momentum_drift").get<double>();
    EXPECT_NEAR(std::stod(last.at(6)), drift, 1e-6 * drift) << name;  // (the CSV's 7 digits)
  }

  r = run_motus(dir, {"compare", scene("head_on"), "--engines", "box2d", "--out", (dir / "b").string(), "--duration", "0.1"});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const auto& row : csv_data_rows(read_file(dir / "b" / "metrics.csv"))) EXPECT_EQ(row.at(12), "") << row.at(1);
}

TEST(Compare, ARunThatBlewUpIsNotReportedAsExact) {
  // Euler on x'' = -x at dt = 3: its energy grows by 1 + 9 a step, past double's range at step 309
  // (below). The exact answer's table said 0 m from it (NaN lost every comparison), the sentence "-nan".
  TempDir dir;
  const Result r = run_motus(dir, {"compare", scene("oscillator"), "--integrator", "euler", "--dt", "3", "--duration",
                                   "3000", "--engines", "motus", "--out", (dir / "r").string(), "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("exact")) << r.out;
  const auto& motus = j.at("exact").at("engines").at(0);
  EXPECT_TRUE(motus.at("final_distance").is_null()) << motus.dump();  // no number, not 0 (nor NaN, which JSON cannot hold)
  EXPECT_EQ(j.at("notice").get<std::string>().find("nan"), std::string::npos) << j.at("notice");
  // When: from (x, v) = (1, 0) each step multiplies x² + v² by exactly 1 + h² = 10, so after n steps the
  // energy is ½·10ⁿ (rounding moves that by some 1e-13, nowhere near a factor). At n = 308, x² and v²
  // are at most 1e308, below double's largest, 1.8e308: finite. At n = 309 the larger of them is at
  // least 10³⁰⁹/2 = 5e308: ∞, and so is the energy. The 1000 steps are sampled 200 times (the default
  // --samples), every 5 steps, so the first sample whose energy is not finite is step 310: t = 930 s.
  constexpr double h = 3;
  const double growth = 1 + h * h, largest = std::numeric_limits<double>::max();
  const long last_finite = static_cast<long>(std::floor(std::log(largest) / std::log(growth)));  // 10ⁿ ≤ largest
  const long first_infinite = static_cast<long>(std::ceil((std::log(largest) + std::log(2.0)) / std::log(growth)));  // 10ⁿ/2 > largest
  ASSERT_EQ(first_infinite, last_finite + 1);  // (the two bounds pin the step: 308 and 309)
  const long every = 1000 / 200, sampled = (first_infinite + every - 1) / every * every;
  const auto& run = *engine(j, "motus");
  EXPECT_EQ(run.at("not_finite_from").get<double>(), static_cast<double>(sampled) * h) << run.dump();  // 310 × 3 s = 930 s
  // And the sentence says so, where it said the run strayed "inf m" from the exact answer.
  const std::string notice = j.at("notice").get<std::string>();
  EXPECT_NE(notice.find("motus not finite from t = " + std::to_string(sampled * 3) + " s on"), std::string::npos) << notice;
  EXPECT_EQ(notice.find("inf m"), std::string::npos) << notice;
}

TEST(Compare, AFigureNoEngineCouldDrawIsStillThereForItsLink) {
  // Box2D cannot run a 3-D scene: the energy figure has no line, and was not drawn, though the
  // report links it. It is drawn as empty axes that say so. (It was the 1-D oscillator, which Box2D
  // now runs on its x axis.) Nothing was timed, and the line above the table says so.
  TempDir dir;
  const Result r = run_motus(dir, {"compare", scene("bouncing_balls_3d"), "--engines", "box2d", "--duration", "0.1",
                                   "--out", (dir / "r").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("us/step: nothing was timed (no engine could run the scene)\n"), std::string::npos) << r.out;
  if (!fs::exists("/usr/bin/gnuplot")) GTEST_SKIP() << "no gnuplot here";
  EXPECT_TRUE(fs::exists(dir / "r" / "energy.svg"));
  EXPECT_TRUE(fs::exists(dir / "r" / "energy.png"));
  // It says there is nothing to draw (it said "every value is exactly 0", on a one-second axis).
  const std::string script = read_file(dir / "r" / "figures.gp");
  EXPECT_NE(script.find("nothing to draw: no run has data for this figure"), std::string::npos);
  EXPECT_EQ(script.find("every value is exactly 0"), std::string::npos);
}

// The table's header line of a compare run's standard output (the line that starts "engine").
std::string table_header(const std::string& out) {
  std::istringstream lines(out);
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("engine ", 0) == 0) return line;
  return "";
}

// The report marks a momentum column that walls or outside forces change with "*" and a note under
// the table; the terminal's table showed free_fall's 1.88e+00 (gravity's push) unmarked. Now both
// mark it, from the one decision (conserved_quantities: momentum_conserved in the summary), with the
// same note; head_on (no walls, no forces) keeps its momentum and is not marked.
TEST(Compare, AMomentumTheSceneDoesNotKeepIsMarkedInTheTableAsInTheReport) {
  TempDir dir;
  const Result fall = run_motus(dir, {"compare", scene("free_fall"), "--engines", "motus", "--repeats", "1", "--out",
                                      (dir / "f").string()});
  ASSERT_EQ(fall.status, 0) << fall.err;
  const std::string note =
      "* This scene does not keep its momentum (walls, pins or outside forces act on it): that column shows their "
      "push, not an engine's error.";
  EXPECT_NE(table_header(fall.out).find(" momentum* "), std::string::npos) << fall.out;
  EXPECT_NE(fall.out.find("\n" + note + "\n"), std::string::npos) << fall.out;
  EXPECT_FALSE(nlohmann::json::parse(read_file(dir / "f" / "summary.json")).at("momentum_conserved").get<bool>());
  const std::string page = read_file(dir / "f" / "index.html");
  EXPECT_NE(page.find("<th scope=\"col\">momentum drift*</th>"), std::string::npos);
  EXPECT_NE(page.find("<p class=\"dim\">" + note + "</p>"), std::string::npos);

  const Result head_on = run_motus(dir, {"compare", scene("head_on"), "--engines", "motus", "--repeats", "1",
                                         "--duration", "0.1", "--out", (dir / "h").string()});
  ASSERT_EQ(head_on.status, 0) << head_on.err;
  EXPECT_NE(table_header(head_on.out).find(" momentum "), std::string::npos) << head_on.out;
  EXPECT_EQ(head_on.out.find("* This scene"), std::string::npos) << head_on.out;
  EXPECT_TRUE(nlohmann::json::parse(read_file(dir / "h" / "summary.json")).at("momentum_conserved").get<bool>());
  EXPECT_NE(read_file(dir / "h" / "index.html").find("<th scope=\"col\">momentum drift</th>"), std::string::npos);
}

// A pendulum's coordinate is its angle θ (scene-format.md): what the momentum columns measure is
// m·θ', the mass times the angular velocity, not a momentum. The table, the summary and the report
// said "momentum" (and, for a pendulum let go at rest, "kg·m/s").
TEST(Compare, APendulumsMomentumColumnIsItsMassTimesItsAngularVelocity) {
  TempDir dir;
  const Result swing = run_motus(dir, {"compare", scene("pendulum"), "--engines", "motus", "--repeats", "1",
                                       "--duration", "1", "--out", (dir / "p").string()});
  ASSERT_EQ(swing.status, 0) << swing.err;
  EXPECT_NE(table_header(swing.out).find(" m theta'* "), std::string::npos) << swing.out;
  EXPECT_NE(swing.out.find("\n* This scene's coordinate is the pendulum's angle θ: that column is the change in m·θ' "),
            std::string::npos)
      << swing.out;
  const auto j = nlohmann::json::parse(read_file(dir / "p" / "summary.json"));
  EXPECT_EQ(j.at("momentum_quantity"), "m·θ'");
  EXPECT_EQ(j.at("coordinate_unit"), "rad");
  EXPECT_EQ(j.at("momentum_unit"), "scale");  // (θ' starts at 5 rad/s)
  const std::string page = read_file(dir / "p" / "index.html");
  EXPECT_NE(page.find("<th scope=\"col\">m·θ' drift*</th>"), std::string::npos);
  EXPECT_NE(page.find("<dt>m·θ' drift</dt>"), std::string::npos);
  EXPECT_EQ(page.find("<th scope=\"col\">momentum drift"), std::string::npos);

  // Let go at rest (θ = 1 rad, θ' = 0): no scale, so the column is the change itself, in kg·rad/s.
  write_file(dir / "rest.json", R"({"name": "rest", "dimensions": 1, "bodies": [{"mass": 1, "position": [1],
    "velocity": [0]}], "forces": [{"type": "pendulum", "g": 9.81, "length": 1}], "integrator": "symplectic-euler",
    "dt": 0.01, "duration": 1})");
  const Result rest = run_motus(dir, {"compare", (dir / "rest.json").string(), "--engines", "motus", "--repeats", "1",
                                      "--out", (dir / "r").string()});
  ASSERT_EQ(rest.status, 0) << rest.err;
  EXPECT_NE(table_header(rest.out).find(" m theta' [kg rad/s]* "), std::string::npos) << rest.out;
  const auto k = nlohmann::json::parse(read_file(dir / "r" / "summary.json"));
  EXPECT_EQ(k.at("momentum_unit"), "kg·rad/s");
  const auto& motus = *engine(k, "motus");
  EXPECT_DOUBLE_EQ(motus.at("momentum_drift").get<double>(), std::abs(motus.at("momentum").at("final")[0].get<double>()));
  EXPECT_NE(read_file(dir / "r" / "index.html").find("<th scope=\"col\">m·θ' drift [kg·rad/s]*</th>"), std::string::npos);
}

// The line above the table says what was timed: it said "one round (engines taking turns), the
// median beside it" of one round (no median of one, no turns) and "no round (no engine ran)
// (engines taking turns)" when nothing ran. Turns are between engines, a median over rounds.
TEST(Compare, TheTimingLineSaysWhatWasTimed) {
  TempDir dir;
  auto timing_line = [&](const std::string& engines, const std::string& repeats) {
    const fs::path out = dir / (engines + "-" + repeats);
    const Result r = run_motus(dir, {"compare", scene("head_on"), "--engines", engines, "--repeats", repeats,
                                     "--duration", "0.1", "--out", out.string()});
    EXPECT_EQ(r.status, 0) << r.err;
    std::istringstream lines(r.out);
    std::string line;
    while (std::getline(lines, line) && line.rfind("us/step:", 0) != 0) {
    }
    return std::make_pair(line, read_file(out / "index.html"));
  };
  const auto [alone_once, alone_once_page] = timing_line("motus", "1");
  EXPECT_EQ(alone_once,
            "us/step: CPU time per step in one timing round; with one round the median is that round and there is "
            "no spread");
  EXPECT_NE(alone_once_page.find("Times are CPU time per step over one timing round."), std::string::npos);
  const auto [two_once, two_once_page] = timing_line("motus,box2d", "1");
  EXPECT_EQ(two_once,
            "us/step: CPU time per step in one timing round, the engines one after another; with one round the median "
            "is that round and there is no spread");
  EXPECT_NE(two_once_page.find("over one timing round, the engines one after another."), std::string::npos);
  const auto [alone_twice, alone_twice_page] = timing_line("motus", "2");
  EXPECT_EQ(alone_twice,
            "us/step: CPU time per step, the fastest of 2 rounds, the median beside it; spread = (slowest - fastest) / "
            "fastest");
  EXPECT_NE(alone_twice_page.find("over 2 timing rounds: the fastest round"), std::string::npos);
  const auto [two_twice, two_twice_page] = timing_line("motus,box2d", "2");
  EXPECT_EQ(two_twice,
            "us/step: CPU time per step, the fastest of 2 rounds (engines taking turns), the median beside it; spread "
            "= (slowest - fastest) / fastest");
  EXPECT_NE(two_twice_page.find("over 2 timing rounds, the engines taking turns in each: the fastest round"),
            std::string::npos);
}

// A fixed-step run takes whole steps: kepler's 2π s at dt = 0.01 s is ⌈628.3⌉ = 629 steps, ending at
// 6.29 s (as motus run says: "time 0 -> 6.29"). The header said "6.28319 s (629 steps)" only.
TEST(Compare, TheHeaderSaysWhenTheRunEndsPastItsDuration) {
  TempDir dir;
  const Result kepler = run_motus(dir, {"compare", scene("kepler"), "--engines", "motus", "--repeats", "1", "--out",
                                        (dir / "k").string()});
  ASSERT_EQ(kepler.status, 0) << kepler.err;
  EXPECT_NE(kepler.out.find("dt = 0.01 s, 6.28319 s (629 steps, ending at t = 6.29 s);"), std::string::npos)
      << kepler.out;
  EXPECT_NE(read_file(dir / "k" / "index.html").find("dt = 0.01 s for 6.28319 s (629 steps, ending at t = 6.29 s);"),
            std::string::npos);
  const auto rows = csv_data_rows(read_file(dir / "k" / "metrics.csv"));
  ASSERT_FALSE(rows.empty());
  EXPECT_NEAR(std::stod(rows.back().at(1)), 6.29, 1e-12);  // where the run did end
  // 0.1 s at 0.01 s is 10 whole steps: nothing to add.
  const Result head_on = run_motus(dir, {"compare", scene("head_on"), "--engines", "motus", "--repeats", "1",
                                         "--duration", "0.1", "--out", (dir / "h").string()});
  ASSERT_EQ(head_on.status, 0) << head_on.err;
  EXPECT_NE(head_on.out.find("dt = 0.01 s, 0.1 s (10 steps);"), std::string::npos) << head_on.out;
}

// The machine's load while the engines were timed: the 1-minute load average as the rounds began
// and ended, and the cores, in the summary and the report; above the cores, a warning in the table
// and the report that ratios between engines may be off (taking turns cannot make rounds of very
// different lengths meet the same load: an audit's ball_gas with 10,000 balls, motus's round 0.04 s, Bullet's
// 23 s). The load is read from MOTUS_LOADAVG's file instead of /proc/loadavg, so that the test does
// not depend on how busy this machine is.
TEST(Compare, TheTimingsSayHowBusyTheMachineWas) {
  TempDir dir;
  const long cores = ::sysconf(_SC_NPROCESSORS_ONLN);
  ASSERT_GT(cores, 0);
  struct Case {
    std::string name, loadavg;  // the file's first number ("" : no such file)
    bool busy;
  };
  const std::vector<Case> cases = {
      {"idle", "0.00", false},
      {"as_many_as_cores", std::to_string(cores) + ".00", false},  // exceeded, not reached
      {"busy", std::to_string(cores) + ".01", true},
      {"unreadable", "", false},
  };
  for (const Case& c : cases) {
    const fs::path file = dir / (c.name + ".loadavg");
    if (!c.loadavg.empty()) write_file(file, c.loadavg + " 0.50 0.40 2/345 6789\n");
    const fs::path out = dir / c.name;
    const Result r = run_motus(dir, {"compare", scene("head_on"), "--engines", "motus", "--repeats", "1", "--duration",
                                     "0.1", "--out", out.string()},
                               {"MOTUS_LOADAVG=" + file.string()});
    ASSERT_EQ(r.status, 0) << c.name << ": " << r.err;
    const auto j = nlohmann::json::parse(read_file(out / "summary.json"));
    EXPECT_EQ(j.at("cores").get<long>(), cores) << c.name;
    EXPECT_EQ(j.at("busy_machine").get<bool>(), c.busy) << c.name;
    const std::string page = read_file(out / "index.html");
    if (c.loadavg.empty()) {
      EXPECT_TRUE(j.at("load_average").at("start").is_null()) << c.name;
      EXPECT_TRUE(j.at("load_average").at("end").is_null()) << c.name;
      EXPECT_NE(page.find("The machine has " + std::to_string(cores) + " core" + (cores == 1 ? "" : "s") +
                          "; its load average could not be read."),
                std::string::npos)
          << c.name;
    } else {
      EXPECT_EQ(j.at("load_average").at("start").get<double>(), std::stod(c.loadavg)) << c.name;
      EXPECT_EQ(j.at("load_average").at("end").get<double>(), std::stod(c.loadavg)) << c.name;
      EXPECT_NE(page.find("The machine's 1-minute load average was " + c.loadavg + " as the timing began and " +
                          c.loadavg + " as it ended, on " + std::to_string(cores) + " core"),
                std::string::npos)
          << c.name;
    }
    const std::string warning = "the timings were taken on a busy machine (a 1-minute load average of " + c.loadavg +
                                " as they began and " + c.loadavg + " as they ended, on " + std::to_string(cores) +
                                " core" + (cores == 1 ? "" : "s") +
                                "): rounds of very different lengths do not meet the same load, so the ratios "
                                "between engines may be off";
    if (c.busy) {
      EXPECT_NE(r.out.find("\nwarning: " + warning + "\n"), std::string::npos) << r.out;
      EXPECT_NE(page.find("<p class=\"no\">T" + warning.substr(1) + ".</p>"), std::string::npos) << c.name;
    } else {
      EXPECT_EQ(r.out.find("busy machine"), std::string::npos) << c.name << ":\n" << r.out;
      EXPECT_EQ(page.find("The timings were taken on a busy machine"), std::string::npos) << c.name;
    }
  }
  // Without MOTUS_LOADAVG, /proc/loadavg's: numbers (whatever they are).
  const Result real = run_motus(dir, {"compare", scene("head_on"), "--engines", "motus", "--repeats", "1",
                                      "--duration", "0.1", "--json", "--out", (dir / "real").string()});
  ASSERT_EQ(real.status, 0) << real.err;
  const auto j = nlohmann::json::parse(real.out);
  EXPECT_TRUE(j.at("load_average").at("start").is_number()) << real.out;
  EXPECT_TRUE(j.at("load_average").at("end").is_number()) << real.out;
  EXPECT_TRUE(j.at("busy_machine").is_boolean()) << real.out;
}

TEST(Compare, BadInputIsOneLineAndExitTwo) {
  TempDir dir;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"compare", scene("lorenz")},                                    // first-order: no bodies
        std::vector<std::string>{"compare", scene("head_on"), "--engines", "motus,havok"},      // unknown engine
        std::vector<std::string>{"compare", scene("head_on"), "--engines", "motus,,box2d"},     // an empty name
        std::vector<std::string>{"compare", scene("head_on"), "--engines", "motus,"},           // a trailing comma
        std::vector<std::string>{"compare", scene("head_on"), "--engines", "motus,box2d,motus"},  // one twice (merged without a word)
        std::vector<std::string>{"compare", scene("head_on"), "--integrator", "rk4"},           // rk4 cannot collide
        std::vector<std::string>{"compare", scene("head_on"), "--set", "bodies[0].mass=-1"}}) {  // a bad scene
    const Result r = run_motus(dir, args);
    EXPECT_EQ(r.status, 2) << args.back() << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_EQ(r.err.rfind("motus: error: ", 0), 0u) << r.err;
  }
  // Without motus among the engines the header names no motus integrator (it named one that ran nothing).
  const Result peers = run_motus(dir, {"compare", scene("head_on"), "--engines", "box2d,bullet", "--out", (dir / "p").string()});
  ASSERT_EQ(peers.status, 0) << peers.err;
  EXPECT_EQ(peers.out.find("motus integrator"), std::string::npos) << peers.out;
}

}  // namespace

// A scene that starts overlapping is moved apart by motus before the first step (docs/scene-format.md,
// "Overlap"), and every engine's penetration column counts that start: one note on standard error
// (never standard output, --json's), the same in the summary and at the top of index.html, and the
// penetration column's meaning does not claim that nothing overlaps. A scene without overlap: none.
TEST(Compare, AStartThatOverlapsIsSaidOnStandardErrorAndInTheReport) {
  TempDir dir;
  const std::string head_on = scene("head_on"), two = (dir / "two.json").string();
  write_file(two, R"({"dimensions": 2, "bodies": [{"mass": 1, "radius": 0.5, "position": [0, 0], "velocity": [0, 0]},
      {"mass": 1, "radius": 0.5, "position": [0.1, 0], "velocity": [0, 0]}], "integrator": "symplectic-euler",
      "dt": 0.01, "duration": 0.1})");
  const std::string note = "bodies 0 and 1 start overlapping by 0.9 m; motus moves them apart before the first step, "
                           "and the penetration column counts that start";
  const fs::path out = dir / "pair";
  const Result pair = run_motus(dir, {"compare", two, "--out", out.string(), "--json"});
  ASSERT_EQ(pair.status, 0) << pair.err;
  EXPECT_EQ(pair.err, "note: " + two + ": " + note + "\n");
  const auto j = nlohmann::json::parse(pair.out);
  EXPECT_EQ(j.value("initial_overlap", ""), note);
  EXPECT_NEAR(engine(j, "motus")->at("max_penetration").get<double>(), 0.9, 1e-9);
  const std::string html = read_file(out / "index.html");
  EXPECT_NE(html.find("<b>Note:</b> " + note + "."), std::string::npos);
  EXPECT_EQ(html.find("Exact collisions never overlap"), std::string::npos);
  EXPECT_NE(html.find("This scene starts overlapping"), std::string::npos);

  const std::string outside = (dir / "outside.json").string();
  write_file(outside, R"({"dimensions": 2, "bodies": [{"mass": 1, "radius": 0.5, "position": [8, 1], "velocity": [0, 0]}],
      "colliders": [{"type": "box", "min": [0, 0], "max": [5, 5]}], "integrator": "symplectic-euler", "dt": 0.01,
      "duration": 0.1})");
  const Result box = run_motus(dir, {"compare", outside, "--engines", "motus", "--out", (dir / "box").string()});
  ASSERT_EQ(box.status, 0) << box.err;
  EXPECT_EQ(box.err, "note: " + outside + ": body 0 starts outside box 0, 3.5 m into its wall; motus moves it into the "
                     "box before the first step, and the penetration column counts that start\n");
  EXPECT_EQ(box.out.find("starts outside"), std::string::npos) << box.out;

  const fs::path plain = dir / "plain";
  const Result none = run_motus(dir, {"compare", head_on, "--duration", "0.1", "--out", plain.string(), "--json"});
  ASSERT_EQ(none.status, 0) << none.err;
  EXPECT_EQ(none.err.find("note:"), std::string::npos) << none.err;
  EXPECT_FALSE(nlohmann::json::parse(none.out).contains("initial_overlap"));
  EXPECT_NE(read_file(plain / "index.html").find("Exact collisions never overlap"), std::string::npos);
}
