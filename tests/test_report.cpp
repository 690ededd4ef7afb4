// What `motus compare`'s report says in words (docs/cli.md, compare/motus/compare/explanations.hpp):
// every column defined, the exact answer and each engine's distance from it where the scene has one
// (head_on, oblique, newtons_cradle, drop, free_fall: "exact": "free-flight"), a sentence of what
// to notice made from the measured numbers, and the first and last frames as a picture.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "accessibility.hpp"
#include "cli_harness.hpp"
#include "motus/render/draw.hpp"
#include "motus/render/image.hpp"

#include <cmath>
#include <cstdio>
#include <array>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace {

using namespace motus_test;

// A number as motus's figures write it (figure.cpp: %.10g).
std::string fmt_number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.10g", x);
  return text;
}

struct Report {
  nlohmann::json summary;
  std::string html;
  fs::path folder;
};

Report compare(const TempDir& dir, const std::string& scene, std::vector<std::string> extra = {},
               const std::string& folder = "") {
  const fs::path out = dir / ("report-" + (folder.empty() ? scene : folder));
  std::vector<std::string> args = {"compare", scene, "--out", out.string(), "--json"};
  args.insert(args.end(), extra.begin(), extra.end());
  const auto r = run_motus(dir, args);
  EXPECT_EQ(r.status, 0) << r.err;
  Report report;
  report.summary = nlohmann::json::parse(r.out);
  report.html = read_file(out / "index.html");
  report.folder = out;
  return report;
}

const nlohmann::json& engine(const Report& r, const std::string& name) {
  for (const auto& e : r.summary["engines"])
    if (e["engine"] == name) return e;
  throw std::runtime_error("no engine " + name);
}

bool is_png(const fs::path& file) {
  const std::string bytes = read_file(file);
  return bytes.size() > 8 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

TEST(Report, DefinesEveryColumnOfItsTable) {
  TempDir dir;
  const auto r = compare(dir, "ball_gas", {"--set", "lattice.count=100", "--duration", "0.5"});
  std::vector<std::string> columns;
  for (const auto& d : r.summary["definitions"]) columns.push_back(d["column"]);
  for (const char* c : {"energy drift", "max |ΔE|/E₀", "momentum drift", "max penetration [m]", "constraint error",
                        "max distance from motus [m]", "µs per step (min)", "median", "spread", "time / motus"}) {
    EXPECT_NE(std::find(columns.begin(), columns.end(), c), columns.end()) << c;
    EXPECT_NE(r.html.find(std::string("<dt>") + c + "</dt>"), std::string::npos) << c;
  }
  // The gas is in a box: its momentum is the walls' push, and the report says so.
  EXPECT_NE(r.html.find("does not keep its momentum"), std::string::npos);
  EXPECT_EQ(r.summary.count("exact"), 0u);  // no exact answer for a gas
  // It keeps its energy: the sentence says so and quotes motus's measured drift.
  const std::string notice = r.summary["notice"];
  EXPECT_NE(notice.find("keeps its energy exactly"), std::string::npos) << notice;
  EXPECT_NE(r.html.find("What to notice"), std::string::npos);
  EXPECT_TRUE(is_png(r.folder / "first_and_last.png"));
  EXPECT_NE(r.html.find("first_and_last.png"), std::string::npos);
}

TEST(Report, NewtonsCradleShowsTheExactAnswerAndEachEnginesDistance) {
  TempDir dir;
  const auto r = compare(dir, "newtons_cradle");
  ASSERT_TRUE(r.summary.contains("exact"));
  const auto& x = r.summary["exact"];
  // Equal masses, e = 1, in contact: the last ball leaves at the striker's 1 m/s, the others rest.
  ASSERT_EQ(x["bodies"].size(), 5u);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(x["bodies"][i]["velocity"][0].get<double>(), 0, 1e-15);
  EXPECT_NEAR(x["bodies"][4]["velocity"][0].get<double>(), 1, 1e-15);
  for (const auto& e : x["engines"]) EXPECT_TRUE(e.contains("max_speed_error")) << e.dump();
  // motus's collisions are exact (time of impact within the step, contacts in turn).
  EXPECT_LT(x["engines"][0]["max_speed_error"].get<double>(), 1e-12);
  EXPECT_LT(engine(r, "motus")["max_distance_from_exact"].get<double>(), 1e-12);
  // Each engine has a distance from the exact answer in the table, and the sentence names them all.
  EXPECT_NE(r.html.find("<th scope=\"col\">max distance from exact [m]</th>"), std::string::npos);
  EXPECT_NE(r.html.find("<h2 id=\"exact-answer\">The exact answer</h2>"), std::string::npos);
  const std::string notice = r.summary["notice"];
  EXPECT_NE(notice.find("ball 4 leaves at (1, 0) m/s and the others rest"), std::string::npos) << notice;
  for (const auto& e : r.summary["engines"])
    if (e["supported"].get<bool>()) {
      EXPECT_NE(notice.find(e["engine"].get<std::string>()), std::string::npos) << notice;
    }
}

// kepler: motus's velocity Verlet ends 0.014 m from the orbit, the peers' symplectic Euler 0.058 m;
// the sentence credited motus with what is the method's (an audit): it now says which method each
// integrated with. With symplectic Euler motus strays as far as Box2D does, measured here.
TEST(Report, TheSentenceSaysWhenMotusIntegratedWithAnotherMethodThanThePeers) {
  TempDir dir;
  const auto own = compare(dir, "kepler", {"--engines", "motus,box2d"});
  EXPECT_NE(own.summary["notice"].get<std::string>().find(
                "motus integrated with velocity-verlet, Box2D and Bullet with symplectic Euler"),
            std::string::npos)
      << own.summary["notice"];
  const auto alike = compare(dir, "kepler", {"--engines", "motus,box2d", "--integrator", "symplectic-euler"}, "alike");
  EXPECT_EQ(alike.summary["notice"].get<std::string>().find("motus integrated with"), std::string::npos)
      << alike.summary["notice"];
  const double motus = engine(alike, "motus")["max_distance_from_exact"].get<double>();
  const double box2d = engine(alike, "box2d")["max_distance_from_exact"].get<double>();
  // (The same steps, Box2D's in floats: each rounds a position of size ~1 m by ~6e-8 m, 629 steps at most
  // 4e-5 m, 7e-4 of the 0.058 m both stray. Measured: 1e-5.)
  EXPECT_NEAR(motus / box2d, 1, 1e-3) << motus << " against " << box2d;
  EXPECT_LT(engine(own, "motus")["max_distance_from_exact"].get<double>(), 0.5 * box2d);
  // Sticks are projected on Verlet alone: no "like with like" to offer there. Their sentence gives each
  // engine's energy change beside its stick error (it ranked the lengths alone, while motus's projection
  // loses 8.8 J of stick_pendulum's 9.8): the json's own figures, in J (E₀ = 0).
  const auto sticks = compare(dir, "stick_pendulum");
  const std::string notice = sticks.summary["notice"];
  EXPECT_EQ(notice.find("like with like"), std::string::npos) << notice;
  for (const auto& e : sticks.summary["engines"])
    if (e["supported"].get<bool>()) {
      const double change = e["energy"]["final"].get<double>() - e["energy"]["initial"].get<double>();
      char text[32];
      std::snprintf(text, sizeof text, "%+.2g", change);  // (the sentence's two figures, signed)
      EXPECT_NE(notice.find(e["engine"].get<std::string>() + " " + text), std::string::npos)
          << notice << " (" << e["engine"] << " " << change << ")";
    }
}

TEST(Report, EveryCollisionSceneWithAnExactAnswerHasItsColumn) {
  TempDir dir;
  for (const char* scene : {"head_on", "oblique", "drop"}) {
    const auto r = compare(dir, scene);
    EXPECT_TRUE(r.summary.contains("exact")) << scene;
    for (const auto& e : r.summary["engines"])
      if (e["supported"].get<bool>()) {
        EXPECT_TRUE(e["max_distance_from_exact"].is_number()) << scene << " " << e["engine"];
      }
    EXPECT_NE(r.html.find("max distance from exact"), std::string::npos) << scene;
  }
}

TEST(Report, FreeFallIsHalfGHTBehindTheParabolaUnderSymplecticEuler) {
  // Symplectic Euler under a constant g: x_n = x0 + v0 t + ½ g t² + ½ g h t, so the distance from
  // the parabola grows as ½ g h t — 0.0981 m after T = 2 s at h = 0.01 s; velocity Verlet is exact.
  TempDir dir;
  const auto r = compare(dir, "free_fall", {"--engines", "motus"});
  EXPECT_NEAR(engine(r, "motus")["max_distance_from_exact"].get<double>(), 0.5 * 9.81 * 0.01 * 2, 1e-9);
  const auto verlet = compare(dir, "free_fall", {"--engines", "motus", "--integrator", "velocity-verlet"}, "verlet");
  EXPECT_LT(engine(verlet, "motus")["max_distance_from_exact"].get<double>(), 1e-12);
  EXPECT_NE(r.summary["notice"].get<std::string>().find("parabola"), std::string::npos);
}

// What the definitions say of the samples and of the timing rounds is what the run did. The maxima
// were "over the 200 samples of the run (and its start and end)", but the last sample is the end
// (comparison.cpp: k·steps/samples, k = 1 … samples): metrics.csv's rows are the start and the
// samples, the last at the end. And taking turns was said to make "a busy machine slow all of them
// alike", which rounds of very different lengths do not (an audit's ball_gas with 10,000 balls:
// motus's round 0.04 s, Bullet's 23 s, on a machine whose load exceeded its cores).
TEST(Report, TheDefinitionsSayHowTheSamplesAndTheRoundsWereTaken) {
  TempDir dir;
  const auto r = compare(dir, "head_on", {"--engines", "motus", "--repeats", "1", "--samples", "50"});
  const auto rows = csv_data_rows(read_file(r.folder / "metrics.csv"));
  ASSERT_EQ(rows.size(), 51u);                     // the start and 50 samples
  EXPECT_EQ(std::stod(rows.front().at(1)), 0.0);
  EXPECT_NEAR(std::stod(rows.back().at(1)), 4.0, 1e-12);  // the last at the end (4 s)
  std::map<std::string, std::string> meaning;
  for (const auto& d : r.summary["definitions"]) meaning[d["column"]] = d["meaning"];
  EXPECT_NE(meaning["max |ΔE|/E₀"].find("over the run's start and its 50 samples (evenly spaced, the last at its end)"),
            std::string::npos)
      << meaning["max |ΔE|/E₀"];
  EXPECT_EQ(r.html.find("(and its start and end)"), std::string::npos);
  const std::string& time = meaning["µs per step (min)"];
  EXPECT_EQ(time.find("slows all of them alike"), std::string::npos) << time;
  EXPECT_NE(time.find("Taking turns cannot make rounds of very different lengths meet the same load"), std::string::npos)
      << time;
}

}  // namespace

namespace {

// Each engine's distance from the exact answer at its end is taken at its own end time: motus adds
// its steps up (head_on ends at t = 3.9999999999999587), Bullet counts them (t = 4), and measured
// at motus's time Bullet's final distance (1.9e-13 m) came out larger than its largest over the run
// (1.1e-13 m), which includes the end.
TEST(Report, AnEnginesFinalDistanceFromExactIsAtMostItsLargest) {
  TempDir dir;
  const auto r = compare(dir, "head_on", {"--repeats", "1"});
  ASSERT_TRUE(r.summary.contains("exact"));
  int engines = 0;
  for (const auto& e : r.summary["exact"]["engines"]) {
    const double largest = engine(r, e["engine"].get<std::string>())["max_distance_from_exact"].get<double>();
    EXPECT_LE(e["final_distance"].get<double>(), largest) << e["engine"];
    ++engines;
  }
  EXPECT_EQ(engines, 3);
}

// One engine keeps one colour in every figure whoever else ran, and one that could not run the
// scene is in the legend, saying so: in the 1-D oscillator Bullet was drawn in Box2D's orange, and
// Box2D was not in the legend at all. (Box2D now runs 1-D scenes on its x axis; it cannot run a
// 3-D one.) Its entry has no sample line (`lt nodraw`): an orange dash beside "box2d: not
// supported" read as a line somewhere in the plot (a pictures audit).
TEST(Report, EveryEngineKeepsItsColourAndOneThatCouldNotRunIsInTheLegend) {
  TempDir dir;
  const auto r = compare(dir, "bouncing_balls_3d", {"--repeats", "1", "--duration", "0.1"});
  const std::string gp = read_file(r.folder / "figures.gp");
  // Every figure's entry for each engine: with its colour, as many times as the figures name it.
  auto count = [&](const std::string& text) {
    long n = 0;
    for (size_t at = gp.find(text); at != std::string::npos; at = gp.find(text, at + 1)) ++n;
    return n;
  };
  // (Each entry is "lc rgb '#4285d6' dt solid title 'motus'": the colour, the dash, the title. The
  // colours are the palette's, plot/motus/plot/figure.cpp, read here from the script.)
  std::set<std::string> colours;
  for (const std::string title : {"title 'motus'", "title 'bullet'"}) {
    EXPECT_GT(count(title), 0) << title << " in:\n" << gp;
    const std::regex entry("lc rgb '(#[0-9a-f]{6})' dt \\S+ " + title);
    std::set<std::string> mine;
    long entries = 0;
    for (auto it = std::sregex_iterator(gp.begin(), gp.end(), entry); it != std::sregex_iterator(); ++it, ++entries)
      mine.insert((*it)[1].str());
    EXPECT_EQ(entries, count(title)) << title << " in:\n" << gp;
    EXPECT_EQ(mine.size(), 1u) << title << " in:\n" << gp;
    colours.insert(mine.begin(), mine.end());
  }
  EXPECT_EQ(colours.size(), 2u) << gp;
  const std::string box2d = "title 'box2d: not supported (3-D scenes)'";
  EXPECT_GT(count(box2d), 0) << gp;
  EXPECT_EQ(count("1/0 with lines lt nodraw " + box2d), count(box2d)) << gp;
}


// Engines that agree draw the same curve: free_fall's energy error is the same in all three, and
// drawn at one width only the last engine's line (Bullet's green) could be seen. Each engine's
// colour must show in the plot itself, not only in the legend below it.
TEST(Report, EnginesThatAgreeAreAllSeenInThePicture) {
  TempDir dir;
  const auto r = compare(dir, "free_fall", {"--repeats", "1"});
  // That they agree to less than a pixel, from the run's own figures: the axis spans 4 decades in
  // about 340 px, 2.7 % a pixel; their largest energy errors are within 1 % of each other.
  const double motus_error = engine(r, "motus")["max_energy_error"].get<double>();
  for (const char* peer : {"box2d", "bullet"})
    ASSERT_NEAR(engine(r, peer)["max_energy_error"].get<double>(), motus_error, 0.01 * motus_error) << peer;
  const motus::render::Image png = motus::render::read_png((r.folder / "energy.png").string());
  // The pixels of each engine's colour above the legend (the bottom 60 rows: the x axis's label and
  // the legend, whose sample lines are in every colour whatever the plot shows), within 24 of it in
  // each channel (a line's edges are blended with what is under them; the three colours are over
  // 70 apart in some channel, so no pixel counts for two).
  auto pixels_of = [&](int red, int green, int blue) {
    long n = 0;
    for (int y = 0; y < png.height - 60; ++y)
      for (int x = 0; x < png.width; ++x) {
        const std::uint8_t* p = &png.rgba[4 * (static_cast<size_t>(y) * static_cast<size_t>(png.width) + static_cast<size_t>(x))];
        n += std::abs(p[0] - red) <= 24 && std::abs(p[1] - green) <= 24 && std::abs(p[2] - blue) <= 24;
      }
    return n;
  };
  // Each engine's colour as the figures' script gives it (the palette of plot/motus/plot/figure.cpp).
  // The curve is about 900 px long; the last line drawn (Bullet's) shows part of it (its dashes),
  // and each line drawn before it shows where the lines over it leave gaps: over 100 px each.
  const std::string gp = read_file(r.folder / "figures.gp");
  auto colour_of = [&](const std::string& engine) {
    std::smatch m;
    if (!std::regex_search(gp, m, std::regex("lc rgb '#([0-9a-f]{6})' dt \\S+ title '" + engine + "'"))) {
      ADD_FAILURE() << engine << " in\n" << gp;
      return std::array<int, 3>{-100, -100, -100};
    }
    const std::string hex = m[1].str();
    return std::array<int, 3>{std::stoi(hex.substr(0, 2), nullptr, 16), std::stoi(hex.substr(2, 2), nullptr, 16),
                              std::stoi(hex.substr(4, 2), nullptr, 16)};
  };
  auto pixels_in = [&](const std::array<int, 3>& c) { return pixels_of(c[0], c[1], c[2]); };
  const long motus = pixels_in(colour_of("motus")), box2d = pixels_in(colour_of("box2d")), bullet = pixels_in(colour_of("bullet"));
  EXPECT_GT(motus, 100) << "motus (box2d " << box2d << ", bullet " << bullet << ")";
  EXPECT_GT(box2d, 100) << "box2d (motus " << motus << ", bullet " << bullet << ")";
  EXPECT_GT(bullet, 100) << "bullet (motus " << motus << ", box2d " << box2d << ")";
}

// A pictures audit: head_on's two balls were blue and orange, motus's and Box2D's colours in the plots
// beside them, and the orange ball read as Box2D's. A comparison's bodies take the palette from its
// fourth colour (render::body_color(3), red, and (4), purple, for head_on's two), in every panel.
TEST(Report, AComparisonsBodiesAreNotInTheEnginesColours) {
  TempDir dir;
  const auto r = compare(dir, "head_on", {"--repeats", "1"});
  const motus::render::Image png = motus::render::read_png((r.folder / "first_and_last.png").string());
  auto pixels_of = [&](const motus::render::Color& c) {
    long n = 0;
    for (size_t p = 0; p + 3 < png.rgba.size(); p += 4)
      n += std::abs(png.rgba[p] - c.r) <= 8 && std::abs(png.rgba[p + 1] - c.g) <= 8 && std::abs(png.rgba[p + 2] - c.b) <= 8;
    return n;
  };
  // Each ball is some 50 px across, in six panels: thousands of pixels of each body's colour.
  EXPECT_GT(pixels_of(motus::render::body_color(3)), 3000);
  EXPECT_GT(pixels_of(motus::render::body_color(4)), 3000);
  for (int engine = 0; engine < 3; ++engine) EXPECT_LT(pixels_of(motus::render::body_color(engine)), 50) << engine;
}

// Found by an audit of what the report's pictures show.
// A run that blew up was drawn as "exactly 0 throughout" (its NaN left out like a log axis's 0), the
// report printed "-nan", and summary.json had null where a reader could not tell "blew up" from
// "no exact answer". Now the legend says from when it is not finite, and the JSON says so.
TEST(Report, ARunThatBlewUpIsDrawnAndWrittenAsNotFinite) {
  TempDir dir;
  const auto r = compare(dir, "oscillator",
                         {"--integrator", "euler", "--dt", "10", "--duration", "20000", "--repeats", "1", "--engines",
                          "motus"});
  const auto& motus = engine(r, "motus");
  // When, from the samples themselves: the first row of metrics.csv whose total energy is not finite.
  double first_not_finite = -1;
  for (const auto& cells : csv_data_rows(read_file(r.folder / "metrics.csv")))
    if (!std::isfinite(std::strtod(cells.at(4).c_str(), nullptr))) {
      first_not_finite = std::strtod(cells.at(1).c_str(), nullptr);
      break;
    }
  ASSERT_GT(first_not_finite, 0) << "explicit Euler at ωh = 10 must blow up within 2,000 steps";
  EXPECT_EQ(motus["not_finite_from"].get<double>(), first_not_finite);
  EXPECT_EQ(motus["max_distance_from_motus"].get<double>(), 0.0);  // itself, also once not finite
  EXPECT_EQ(r.html.find("nan"), std::string::npos);
  EXPECT_NE(r.html.find("motus blew up"), std::string::npos);
  const std::string gp = read_file(r.folder / "figures.gp");
  EXPECT_NE(gp.find("motus: not finite from t = " + fmt_number(first_not_finite) + " s (blew up)"), std::string::npos) << gp;
  EXPECT_EQ(gp.find("exactly 0 throughout"), std::string::npos) << gp;
}

// The drop loses energy by design (e = 0.8): its figure was titled "energy error" with "0 is
// exact" under it, calling the bounces' loss every engine's error.
TEST(Report, AnEnergyLostByDesignIsDrawnAsAChangeNotAnError) {
  TempDir dir;
  const auto drop = compare(dir, "drop", {"--repeats", "1", "--engines", "motus"});
  const std::string gp = read_file(drop.folder / "figures.gp");
  EXPECT_NE(gp.find("drop: energy change against time"), std::string::npos) << gp;
  EXPECT_NE(gp.find("loses energy by design"), std::string::npos) << gp;
  EXPECT_EQ(gp.find("0 is exact"), std::string::npos) << gp;
  // The loss is a large part of E0: drawn signed, on a linear axis. On a log axis of |E - E0|
  // bouncing_balls' three engines (0.877, 0.889 and 0.902 of E0 lost) lay along its top edge, and
  // ragdoll's on a symlog one along its bottom edge (a pictures audit).
  const std::string energy_figure = gp.substr(0, gp.find("set output 'energy.png'"));
  EXPECT_NE(energy_figure.rfind("set ylabel '(E - E0) / |E0|'"), std::string::npos) << gp;
  EXPECT_NE(energy_figure.rfind("unset logscale y"), std::string::npos) << gp;
  const auto kepler = compare(dir, "kepler", {"--repeats", "1", "--engines", "motus", "--duration", "1"});
  EXPECT_NE(read_file(kepler.folder / "figures.gp").find("kepler: energy error against time"), std::string::npos);
}

// A pendulum's coordinate is its angle: the report said "max distance from exact [m]" and "m/s"
// beside the sentence's "rad".
TEST(Report, APendulumsDistancesAndSpeedsAreInRadians) {
  TempDir dir;
  const auto r = compare(dir, "pendulum", {"--repeats", "1", "--engines", "motus"});
  EXPECT_NE(r.html.find("max distance from exact [rad]"), std::string::npos);
  EXPECT_NE(r.html.find("max distance from motus [rad]"), std::string::npos);
  EXPECT_EQ(r.html.find("from exact [m]"), std::string::npos);
  EXPECT_NE(r.html.find("velocity [rad/s]"), std::string::npos);
  EXPECT_EQ(r.html.find(" m/s</td>"), std::string::npos);
}

// Newton's cradle starts with L₀ = 0: its angular momentum was drawn in kg·m²/s under the label
// "|L - L0| / |L0|".
TEST(Report, AChangeFromNothingIsLabelledInItsUnit) {
  TempDir dir;
  const auto r = compare(dir, "newtons_cradle", {"--repeats", "1"});
  const std::string gp = read_file(r.folder / "figures.gp");
  EXPECT_NE(gp.find("|L - L0| [kg m^2/s]   (L0 = 0)"), std::string::npos) << gp;
  EXPECT_EQ(gp.find("|L - L0| / |L0|"), std::string::npos) << gp;
}

// The symlog energy axis of stick_pendulum ran from −8.79 J to +0.0726 J exactly, its lines along
// the frame, with labels only down to −1e-01 and up to 1e-06 (a threshold of 1e-16 J, fixed). Now
// it reaches the next whole decade beyond the data on each side, labelled.
TEST(Report, ASymlogAxisReachesTheNextDecadeBeyondItsData) {
  TempDir dir;
  const auto r = compare(dir, "stick_pendulum", {"--repeats", "1"});
  double low = 0, high = 0;
  for (const auto& cells : csv_data_rows(read_file(r.folder / "metrics.csv"))) {
    const double e = std::strtod(cells.at(5).c_str(), nullptr);  // energy_error, J (E₀ = 0)
    low = std::min(low, e), high = std::max(high, e);
  }
  ASSERT_LT(low, 0);
  ASSERT_GT(high, 0);
  const double bottom = -std::pow(10.0, std::ceil(std::log10(-low))), top = std::pow(10.0, std::ceil(std::log10(high)));
  const std::string gp = read_file(r.folder / "figures.gp");
  EXPECT_NE(gp.find("set yrange [" + fmt_number(bottom) + ":" + fmt_number(top) + "]"), std::string::npos) << gp;
  char label[32];
  std::snprintf(label, sizeof label, "'-%.0e' %s", -bottom, fmt_number(bottom).c_str());
  EXPECT_NE(gp.find(label), std::string::npos) << label << " in\n" << gp;
}

// compare's stick error was the largest over its 200 samples (ragdoll: motus 0.052), while motus
// run, bench_constraints and the peers' notes take every step (0.057): the same quantity with two
// numbers. Now compare takes every step too, and agrees with run.
TEST(Report, TheStickErrorIsOverEveryStepAsRunMeasuresIt) {
  TempDir dir;
  const auto r = compare(dir, "ragdoll", {"--repeats", "1", "--engines", "motus"});
  const auto run = run_motus(dir, {"run", "ragdoll", "--json", "--repeats", "1"});
  ASSERT_EQ(run.status, 0) << run.err;
  const auto j = nlohmann::json::parse(run.out);
  EXPECT_EQ(engine(r, "motus")["constraint_error"].get<double>(), j["constraint_error"]["max"].get<double>());
}

// Found by an accessibility audit of the pages. With JavaScript off, the replay showed blank canvases
// and controls that did nothing, its "needs JavaScript" message last; the canvases had no name, the
// step buttons were named by glyphs, and a <style> sat inside the section (not allowed there). Now
// what needs the script is hidden until it runs, the message comes first, and everything is named.
TEST(Report, TheReplayIsHiddenUntilItsScriptRunsAndEveryPartIsNamed) {
  TempDir dir;
  const auto r = compare(dir, "bouncing_balls_3d", {"--duration", "0.2", "--repeats", "1"});
  const size_t start = r.html.find("<section id=\"replay\""), end = r.html.find("</section>", start);
  ASSERT_NE(start, std::string::npos);
  ASSERT_NE(end, std::string::npos);
  const std::string section = r.html.substr(start, end - start);
  // The message first, then the panels, the controls and the notes, each hidden.
  const size_t message = section.find("<noscript><p class=\"no\">The replay needs JavaScript.</p></noscript>");
  ASSERT_NE(message, std::string::npos) << section;
  for (const char* part : {"<div class=\"replay-panels\" hidden>", "<div class=\"replay-controls\" hidden>",
                           "<p class=\"replay-notes\" hidden>"}) {
    const size_t at = section.find(part);
    EXPECT_NE(at, std::string::npos) << part << " in\n" << section;
    EXPECT_LT(message, at) << part;
  }
  // ... and `hidden` wins over the section's display:flex rules.
  EXPECT_NE(r.html.find("#replay [hidden]{display:none!important}"), std::string::npos);
  // No <style> in the body: the replay's CSS is in the head's.
  const size_t body = r.html.find("<body>");
  ASSERT_NE(body, std::string::npos);
  EXPECT_EQ(r.html.find("<style", body), std::string::npos);
  EXPECT_LT(r.html.find("#replay .replay-panels{"), body);
  // A canvas for each engine that ran (Box2D cannot: a 3-D scene), a picture named after its engine.
  for (const auto& e : r.summary["engines"]) {
    const std::string canvas = "role=\"img\" aria-label=\"" + e["engine"].get<std::string>() + " at the frame shown\"";
    EXPECT_EQ(section.find(canvas) != std::string::npos, e["supported"].get<bool>()) << canvas << " in\n" << section;
  }
  EXPECT_NE(section.find("class=\"replay-back\" title=\"one frame back (&larr;)\" aria-label=\"one frame back\""),
            std::string::npos) << section;
  EXPECT_NE(section.find("class=\"replay-forward\" title=\"one frame forward (&rarr;)\" aria-label=\"one frame forward\""),
            std::string::npos) << section;
}

// Found by an accessibility audit: no <html lang> or viewport; tables whose cells a screen reader
// could not read by their headers (no caption, no scope, the engine in a <td>), the momentum note a
// row of the table, "median" without its unit; grey text (.dim, #777) at 4.48:1 on white, under
// AA's 4.5; and an engine that did not run had an empty list under Settings.
TEST(Report, ThePageIsNamedItsTablesHaveHeadersAndItsTextHasContrast) {
  TempDir dir;
  // (Box2D cannot run it: a 3-D scene. It was the 1-D oscillator, which Box2D now runs.)
  const auto r = compare(dir, "bouncing_balls_3d", {"--repeats", "1", "--duration", "0.1"});
  EXPECT_TRUE(starts_as_a_page(r.html));
  EXPECT_TRUE(tables_have_headers(r.html));
  EXPECT_NE(r.html.find("<th scope=\"col\">median [µs]</th>"), std::string::npos);
  // The balls are in a box: the note on the momentum column, after the table.
  const size_t note = r.html.find("<p class=\"dim\">* This scene does not keep its momentum");
  ASSERT_NE(note, std::string::npos) << r.html;
  EXPECT_LT(r.html.find("</table>"), note);
  // Every text colour of the page's CSS, against the white page: 4.5:1 at least.
  const std::string style = r.html.substr(0, r.html.find("</style>"));
  const std::regex colour("[{;]color:(#[0-9a-f]{3}(?:[0-9a-f]{3})?)[;}]");
  int colours = 0;
  for (auto it = std::sregex_iterator(style.begin(), style.end(), colour); it != std::sregex_iterator(); ++it, ++colours)
    EXPECT_GE(contrast_ratio((*it)[1].str(), "#ffffff"), 4.5) << (*it)[0];
  EXPECT_GE(colours, 4) << style;
  // Box2D's settings say it did not run, and why; no list is empty.
  const size_t settings = r.html.find("<h2>Settings</h2>");
  ASSERT_NE(settings, std::string::npos);
  const size_t box2d = r.html.find("<h3>box2d ", settings);
  ASSERT_NE(box2d, std::string::npos);
  std::string why;
  for (const auto& u : engine(r, "box2d")["unsupported"]) why += (why.empty() ? "" : "; ") + u.get<std::string>();
  EXPECT_EQ(r.html.find("<p>not run: " + why + "</p>", box2d), r.html.find("</h3>", box2d) + 6) << r.html.substr(box2d, 400);
  EXPECT_EQ(r.html.find("<ul>\n</ul>"), std::string::npos);
}

// Found by an accessibility audit: Box2D's dash, (40,20), was longer than the legend's sample line
// (about 35 px), so the sample looked solid, like motus's. In the SVG written, every dashed sample
// (a horizontal stretch, the first of its path) now holds a whole period of its pattern, and the
// engines' patterns differ.
TEST(Report, EachEnginesDashShowsInItsLegendSample) {
  TempDir dir;
  const auto r = compare(dir, "free_fall", {"--repeats", "1"});
  const std::string svg = read_file(r.folder / "energy.svg");
  const std::regex sample(R"(stroke-dasharray='([0-9.,]+)'\s+d='M([0-9.]+),([0-9.]+) L([0-9.]+),([0-9.]+) )");
  std::set<std::string> patterns;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), sample); it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    if (m[3].str() != m[5].str()) continue;  // not horizontal: not a legend sample
    double period = 0;
    std::stringstream lengths(m[1].str());
    for (std::string length; std::getline(lengths, length, ',');) period += std::stod(length);
    EXPECT_LE(period, std::stod(m[4].str()) - std::stod(m[2].str())) << m[0];
    patterns.insert(m[1].str());
  }
  EXPECT_EQ(patterns.size(), 2u) << "Box2D's and Bullet's (motus's is solid):\n" << svg.substr(0, 4000);
}

}  // namespace
