// The replay in `motus compare`'s report, in a real browser (docs/cli.md, "The replay"): Debian's
// headless Chromium opens file://…/index.html?t=T and takes a screenshot, and the test finds each
// ball where the recorded positions (replay-data.js; the radii from the scene file) and the documented
// layout (compare/replay/replay.js) put it, in that ball's colour, with background between the balls.
// Every position checked is computed here from the data; no pixel position is written down.
//
// The browser is Debian's `chromium` (debian-packages.txt), started directly with an argument vector
// (never through a shell): --no-sandbox because CI runs as root, a profile folder of the test's own,
// and --virtual-time-budget so that the page's scripts have run before the picture or the DOM is taken.
#include <png.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli_harness.hpp"
#include "motus/plot/figure.hpp"

namespace {

using namespace motus_test;

// The documented layout (compare/replay/replay.js; docs/cli.md), in CSS pixels.
constexpr double kPadding = 16, kGap = 16, kTitle = 40, kCaption = 40, kDefaultSize = 288;
constexpr int kWindowWidth = 1280, kWindowHeight = 900;
using Colour = std::array<int, 3>;
// The palette of the pictures (render/motus/render/frame.cpp, body_color), the canvas's background
// and the background of the box that says why an engine did not run.
constexpr Colour kPalette[8] = {{66, 133, 214}, {230, 120, 50}, {70, 170, 100}, {205, 70, 90},
                                {145, 100, 200}, {40, 170, 180}, {220, 180, 40}, {150, 110, 80}};
constexpr Colour kBackground = {0xf4, 0xf6, 0xf8}, kReasonBackground = {0xfb, 0xee, 0xee};

// `chromium` on PATH, or nothing.
std::optional<std::string> find_chromium() {
  const char* path = std::getenv("PATH");
  std::stringstream folders(path ? path : "");
  for (std::string folder; std::getline(folders, folder, ':');) {
    const fs::path candidate = fs::path(folder.empty() ? "." : folder) / "chromium";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return std::nullopt;
}

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
};

Image read_png(const fs::path& file) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  Image out;
  if (!png_image_begin_read_from_file(&image, file.c_str())) {
    ADD_FAILURE() << file << ": " << image.message;
    return out;
  }
  image.format = PNG_FORMAT_RGB;
  out.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, out.rgb.data(), 0, nullptr)) {
    ADD_FAILURE() << file << ": " << image.message;
    return Image{};
  }
  out.width = static_cast<int>(image.width);
  out.height = static_cast<int>(image.height);
  return out;
}

// replay-data.js is a comment and `window.MOTUS_REPLAY = {…};`: the object is JSON.
nlohmann::json read_replay_data(const fs::path& file) {
  const std::string text = read_file(file);
  const size_t start = text.find("window.MOTUS_REPLAY = "), end = text.rfind('}');
  if (start == std::string::npos || end == std::string::npos || end < start) {
    ADD_FAILURE() << file << ": no window.MOTUS_REPLAY = {...}";
    return nlohmann::json::object({{"engines", nlohmann::json::array()}});
  }
  const size_t open = text.find('{', start);
  return nlohmann::json::parse(text.substr(open, end - open + 1));
}

// The report of one scene, and what the test itself reads from the data and the scene file.
struct Report {
  fs::path folder;
  nlohmann::json data;
  int dimensions = 2;
  std::vector<double> radius;  // every body's, from the scene file
  // The view (replay.js): the walls' box if there is one, else every body's disc at every frame of
  // every engine that ran.
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;

  const nlohmann::json& engine(size_t k) const { return data.at("engines").at(k); }
  size_t engines() const { return data.at("engines").size(); }
  // Body i of engine k at the frame nearest t: (x, y[, z]).
  std::vector<double> position(size_t k, size_t frame, size_t i) const {
    std::vector<double> p;
    for (int c = 0; c < dimensions; ++c) p.push_back(engine(k).at("x").at(frame).at(i * dimensions + c).get<double>());
    return p;
  }
};

Report make_report(const TempDir& dir, const std::string& name, const std::vector<std::string>& extra = {}) {
  Report report;
  report.folder = dir / "report";
  std::vector<std::string> args = {"compare", scene(name), "--out", report.folder.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const Result r = run_motus(dir, args);
  EXPECT_EQ(r.status, 0) << r.err;
  report.data = read_replay_data(report.folder / "replay-data.js");
  const auto file = nlohmann::json::parse(read_file(scene(name)));
  report.dimensions = file.at("dimensions");
  for (const auto& body : file.at("bodies")) report.radius.push_back(body.value("radius", 0.0));
  if (file.contains("colliders"))
    for (const auto& c : file.at("colliders"))
      if (c.at("type") == "box") {
        report.x0 = std::min(report.x0, c.at("min")[0].get<double>()), report.x1 = std::max(report.x1, c.at("max")[0].get<double>());
        report.y0 = std::min(report.y0, c.at("min")[1].get<double>()), report.y1 = std::max(report.y1, c.at("max")[1].get<double>());
      }
  if (report.x0 <= report.x1) return report;
  for (size_t k = 0; k < report.engines(); ++k) {
    if (!report.engine(k).at("supported").get<bool>()) continue;
    for (size_t f = 0; f < report.engine(k).at("x").size(); ++f)
      for (size_t i = 0; i < report.radius.size(); ++i) {
        const auto p = report.position(k, f, i);
        const double r = report.radius[i];
        report.x0 = std::min(report.x0, p[0] - r), report.x1 = std::max(report.x1, p[0] + r);
        report.y0 = std::min(report.y0, p[1] - r), report.y1 = std::max(report.y1, p[1] + r);
      }
  }
  return report;
}

// Where the layout puts a point (x, y) of the scene in engine k's panel, in CSS pixels of the window.
struct Layout {
  double size = kDefaultSize;
  double x0, y0, x1, y1;  // the view
  explicit Layout(const Report& r) : x0(r.x0), y0(r.y0), x1(r.x1), y1(r.y1) {}
  int per_row() const {
    return std::max(1, static_cast<int>(std::floor((kWindowWidth - 2 * kPadding + kGap) / (size + kGap))));
  }
  std::pair<double, double> canvas_corner(size_t k) const {
    const int n = per_row(), column = static_cast<int>(k) % n, row = static_cast<int>(k) / n;
    return {kPadding + column * (size + kGap), kTitle + row * (kCaption + size + kGap) + kCaption};
  }
  double pixels_per_metre() const {
    const double extent = std::max(x1 - x0, y1 - y0);
    return 0.9 * size / (extent > 0 ? extent : 1);
  }
  std::pair<double, double> pixel(size_t k, double x, double y) const {
    const auto [left, top] = canvas_corner(k);
    const double s = pixels_per_metre();
    return {left + size / 2 + (x - (x0 + x1) / 2) * s, top + size / 2 - (y - (y0 + y1) / 2) * s};
  }
};

size_t nearest_frame(const nlohmann::json& times, double t) {
  size_t best = 0;
  for (size_t f = 1; f < times.size(); ++f)
    if (std::abs(times[f].get<double>() - t) < std::abs(times[best].get<double>() - t)) best = f;
  return best;
}

// The time the script shows at the frame nearest t: "t = 1.00 s", with decimals enough for the
// frames' spacing, two at least (replay.js).
std::string shown_time(const nlohmann::json& times, double t) {
  const double spacing = (times.back().get<double>() - times.front().get<double>()) / static_cast<double>(times.size() - 1);
  const int decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(spacing) - 1e-9)), 2, 6);
  char text[64];
  std::snprintf(text, sizeof text, "t = %.*f s", decimals, times[nearest_frame(times, t)].get<double>());
  return text;
}

// The page at URL in headless Chromium: a screenshot into `png`, or, without one, the DOM after the
// scripts have run (on standard output).
Result open_page(const TempDir& dir, const std::string& chromium, const std::string& url, const fs::path& png = {},
                 int device_pixel_ratio = 1, int window_height = kWindowHeight) {
  std::vector<std::string> args = {"--headless", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
                                   "--disable-dev-shm-usage", "--no-first-run", "--mute-audio",
                                   "--user-data-dir=" + (dir / "chromium-profile").string(),
                                   "--window-size=" + std::to_string(kWindowWidth) + "," + std::to_string(window_height),
                                   "--force-device-scale-factor=" + std::to_string(device_pixel_ratio),
                                   "--enable-logging=stderr", "--v=0", "--virtual-time-budget=3000"};
  args.push_back(png.empty() ? std::string("--dump-dom") : "--screenshot=" + png.string());
  args.push_back(url);
  return run_program(dir, chromium, args);
}

std::string page_url(const Report& report, const std::string& tail) {
  return "file://" + fs::absolute(report.folder / "index.html").string() + tail;
}

// A script error on the page: Chromium logs uncaught exceptions as console messages on standard error.
void expect_no_script_errors(const Result& r) {
  EXPECT_EQ(r.err.find("Uncaught"), std::string::npos) << r.err;
}

// The picture's colour at CSS pixel (x, y): the device pixel that holds that point.
std::optional<Colour> colour_at(const Image& image, std::pair<double, double> at, int dpr) {
  const int px = static_cast<int>(std::floor(at.first * dpr)), py = static_cast<int>(std::floor(at.second * dpr));
  if (px < 0 || py < 0 || px >= image.width || py >= image.height) return std::nullopt;
  const unsigned char* c = &image.rgb[(static_cast<size_t>(py) * image.width + px) * 3];
  return Colour{c[0], c[1], c[2]};
}

std::string describe(std::pair<double, double> at, const std::optional<Colour>& c) {
  std::ostringstream s;
  s << "at CSS pixel (" << at.first << ", " << at.second << ") ";
  if (c)
    s << "rgb(" << (*c)[0] << ", " << (*c)[1] << ", " << (*c)[2] << ")";
  else
    s << "outside the picture";
  return s.str();
}

// Whether the picture is `want` at CSS pixel (x, y), to a few units (rounding, colour conversion).
::testing::AssertionResult has_colour(const Image& image, std::pair<double, double> at, int dpr, const Colour& want) {
  const auto c = colour_at(image, at, dpr);
  const bool close = c && std::abs((*c)[0] - want[0]) <= 8 && std::abs((*c)[1] - want[1]) <= 8 && std::abs((*c)[2] - want[2]) <= 8;
  auto result = close ? ::testing::AssertionSuccess() : ::testing::AssertionFailure();
  return result << describe(at, c) << ", expected rgb(" << want[0] << ", " << want[1] << ", " << want[2] << ")";
}

// Whether the picture is a darker shade of `fill` at (x, y): the rim of a ball.
::testing::AssertionResult is_darker(const Image& image, std::pair<double, double> at, int dpr, const Colour& fill) {
  const auto c = colour_at(image, at, dpr);
  const bool darker = c && (*c)[0] + (*c)[1] + (*c)[2] < 0.85 * (fill[0] + fill[1] + fill[2]) &&
                      (*c)[0] <= fill[0] && (*c)[1] <= fill[1] && (*c)[2] <= fill[2];
  auto result = darker ? ::testing::AssertionSuccess() : ::testing::AssertionFailure();
  return result << describe(at, c) << ", expected darker than rgb(" << fill[0] << ", " << fill[1] << ", " << fill[2] << ")";
}

// Every body of every engine that ran, at the frame nearest t, as a disc of its radius in its colour:
// the colour at its centre and 3.5 px inside its edge (left, right, up, down), a darker rim 1 px inside
// the edge, background 2.5 px outside it (where no other body is); and background halfway between
// bodies 0 and 1 (where they are apart) and three radii above body 0.
// Body i's colour in a comparison: the palette's, from the place after the engines' three (motus blue,
// Box2D orange, Bullet green: head_on's orange ball read as Box2D's; a pictures audit).
const Colour& body_colour(size_t i) { return kPalette[(i + motus::plot::kEngineColour::first_free) % 8]; }

void expect_bodies_at(const Report& report, const Image& image, double t, int dpr) {
  const Layout layout(report);
  const double s = layout.pixels_per_metre();
  for (size_t k = 0; k < report.engines(); ++k) {
    const auto& e = report.engine(k);
    if (!e.at("supported").get<bool>()) continue;
    const std::string name = e.at("name");
    const size_t f = nearest_frame(e.at("t"), t);
    auto covered = [&](double x, double y, size_t except) {  // within a pixel of another body's disc
      for (size_t j = 0; j < report.radius.size(); ++j) {
        const auto q = report.position(k, f, j);
        if (j != except && std::hypot(x - q[0], y - q[1]) * s < report.radius[j] * s + 1) return true;
      }
      return false;
    };
    for (size_t i = 0; i < report.radius.size(); ++i) {
      const auto p = report.position(k, f, i);
      const Colour& colour = body_colour(i);
      const std::string where = name + ", body " + std::to_string(i) + " at (" + std::to_string(p[0]) + ", " +
                                std::to_string(p[1]) + ") at t = " + e.at("t")[f].dump();
      EXPECT_TRUE(has_colour(image, layout.pixel(k, p[0], p[1]), dpr, colour)) << where << ": centre";
      const double r = report.radius[i] * s;  // CSS pixels
      if (r < 8) continue;
      for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
        auto at = [&](double pixels) { return layout.pixel(k, p[0] + dx * pixels / s, p[1] + dy * pixels / s); };
        EXPECT_TRUE(has_colour(image, at(r - 3.5), dpr, colour)) << where << ": inside its edge";
        EXPECT_TRUE(is_darker(image, at(r - 1), dpr, colour)) << where << ": its rim";
        if (!covered(p[0] + dx * (r + 2.5) / s, p[1] + dy * (r + 2.5) / s, i)) {
          EXPECT_TRUE(has_colour(image, at(r + 2.5), dpr, kBackground)) << where << ": outside its edge";
        }
      }
    }
    const auto a = report.position(k, f, 0), b = report.position(k, f, 1);
    const double gap = std::hypot(b[0] - a[0], b[1] - a[1]) - report.radius[0] - report.radius[1];
    if (gap * layout.pixels_per_metre() > 4) {
      EXPECT_TRUE(has_colour(image, layout.pixel(k, (a[0] + b[0]) / 2, (a[1] + b[1]) / 2), dpr, kBackground))
          << name << ": between the bodies at t = " << e.at("t")[f];
    }
    EXPECT_TRUE(has_colour(image, layout.pixel(k, a[0], a[1] + 3 * report.radius[0]), dpr, kBackground))
        << name << ": above body 0 at t = " << e.at("t")[f];
  }
}

size_t supported_engines(const Report& report) {
  size_t n = 0;
  for (size_t k = 0; k < report.engines(); ++k) n += report.engine(k).at("supported").get<bool>();
  return n;
}

size_t occurrences(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

class ReplayBrowser : public ::testing::Test {
protected:
  void SetUp() override {
    const auto found = find_chromium();
    if (!found) FAIL() << "chromium not found on PATH: install Debian's chromium package (apt-get install chromium; it is in debian-packages.txt)";
    chromium = *found;
  }
  std::string chromium;
};

// head_on (scenes/head_on.json): balls of masses 1 and 3 at x = -2 and 2, moving at +1 and -1 m/s,
// meet at t = 1.5 s; the light one goes back at -2 m/s and the heavy one stops.
TEST_F(ReplayBrowser, BeforeTheCollisionEveryBallIsWhereTheDataPutsIt) {
  TempDir dir;
  const Report report = make_report(dir, "head_on");
  ASSERT_EQ(report.engines(), 3u);
  ASSERT_EQ(supported_engines(report), 3u);
  // The data: the first frame is the scene file's start, the last the end of the run (4 s).
  for (size_t k = 0; k < report.engines(); ++k) {
    const auto& e = report.engine(k);
    EXPECT_DOUBLE_EQ(e.at("t").front().get<double>(), 0) << e.at("name");
    EXPECT_NEAR(e.at("t").back().get<double>(), 4, 1e-9) << e.at("name");
    EXPECT_NEAR(report.position(k, 0, 0)[0], -2, 1e-6) << e.at("name");
    EXPECT_NEAR(report.position(k, 0, 1)[0], 2, 1e-6) << e.at("name");
    EXPECT_EQ(e.at("x").size(), e.at("t").size());
    EXPECT_EQ(e.at("energy_error").size(), e.at("t").size());
  }
  // The section comes right after the summary table (the first table; closing tags of its wrapper aside).
  const std::string html = read_file(report.folder / "index.html");
  const size_t table = html.find("</table>"), section = html.find("<section id=\"replay\"");
  ASSERT_NE(table, std::string::npos);
  ASSERT_NE(section, std::string::npos);
  ASSERT_LT(table, section);
  std::string between = html.substr(table + 8, section - table - 8);
  for (const std::string tag : {"</div>", "\n", " "})
    for (size_t at; (at = between.find(tag)) != std::string::npos;) between.erase(at, tag.size());
  EXPECT_EQ(between, "") << "between the summary table and the replay";

  const fs::path png = dir / "t1.png";
  const Result r = open_page(dir, chromium, page_url(report, "?t=1.0"), png);
  ASSERT_EQ(r.status, 0) << r.err;
  expect_no_script_errors(r);
  const Image image = read_png(png);
  ASSERT_EQ(image.width, kWindowWidth);
  expect_bodies_at(report, image, 1.0, 1);
}

// At t = 3 s, at a device pixel ratio of 2 (the canvas draws in device pixels): the light ball
// (body 0) has gone back to the left, and where it was at t = 1 s is background.
TEST_F(ReplayBrowser, AfterTheCollisionTheLightBallHasMovedLeft) {
  TempDir dir;
  const Report report = make_report(dir, "head_on");
  ASSERT_EQ(supported_engines(report), 3u);
  const fs::path png = dir / "t3.png";
  const Result r = open_page(dir, chromium, page_url(report, "?t=3.0"), png, 2);
  ASSERT_EQ(r.status, 0) << r.err;
  expect_no_script_errors(r);
  const Image image = read_png(png);
  ASSERT_EQ(image.width, 2 * kWindowWidth);
  expect_bodies_at(report, image, 3.0, 2);
  const Layout layout(report);
  for (size_t k = 0; k < report.engines(); ++k) {
    const auto& e = report.engine(k);
    const auto before = report.position(k, nearest_frame(e.at("t"), 1.0), 0);
    const auto after = report.position(k, nearest_frame(e.at("t"), 3.0), 0);
    EXPECT_LT(after[0], before[0] - 2 * report.radius[0]) << e.at("name");
    EXPECT_TRUE(has_colour(image, layout.pixel(k, before[0], before[1]), 2, kBackground)) << e.at("name");
    EXPECT_LT(layout.pixel(k, after[0], after[1]).first, layout.pixel(k, before[0], before[1]).first) << e.at("name");
  }
}

// A time past the end shows the last frame.
TEST_F(ReplayBrowser, ATimePastTheEndShowsTheLastFrame) {
  TempDir dir;
  const Report report = make_report(dir, "head_on");
  const fs::path png = dir / "end.png";
  const Result r = open_page(dir, chromium, page_url(report, "?t=1000"), png);
  ASSERT_EQ(r.status, 0) << r.err;
  expect_no_script_errors(r);
  const Image image = read_png(png);
  const double end = report.engine(0).at("t").back().get<double>();
  expect_bodies_at(report, image, end, 1);
  const Layout layout(report);  // and not the first frame
  for (size_t k = 0; k < report.engines(); ++k) {
    const auto start = report.position(k, 0, 0);
    EXPECT_TRUE(has_colour(image, layout.pixel(k, start[0], start[1]), 1, kBackground)) << report.engine(k).at("name");
  }
}

// The labels the script writes: each panel's time and energy error at the frame shown, the clock
// (here through the fragment form, #t=).
TEST_F(ReplayBrowser, EveryPanelSaysItsTimeAndEnergyError) {
  TempDir dir;
  const Report report = make_report(dir, "head_on");
  const Result r = open_page(dir, chromium, page_url(report, "#t=1.0"));
  ASSERT_EQ(r.status, 0) << r.err;
  expect_no_script_errors(r);
  const auto& times = report.engine(0).at("t");
  const size_t f = nearest_frame(times, 1.0);
  const std::string label = "<span class=\"replay-time\">" + shown_time(times, 1.0) + "</span>";
  EXPECT_EQ(occurrences(r.out, label), supported_engines(report)) << label << "\n" << r.out;
  EXPECT_EQ(occurrences(r.out, "<span class=\"replay-energy\">\u0394E/E\u2080 = "), supported_engines(report)) << r.out;
  const std::string clock = "frame " + std::to_string(f + 1) + " of " + std::to_string(times.size());
  EXPECT_NE(r.out.find(clock), std::string::npos) << clock << "\n" << r.out;
  EXPECT_NE(r.out.find("replay-theatre"), std::string::npos) << "?t= opens the replay over the window";
}

// An engine that cannot run the scene keeps its place with a box saying why (Box2D and a 3-D scene),
// and the 3-D scene is seen along -z: the nearest ball (largest z) of each engine that ran is drawn
// over the others, in its colour.
TEST_F(ReplayBrowser, AnEngineThatCannotRunTheSceneKeepsItsPanelSayingWhy) {
  TempDir dir;
  const Report report = make_report(dir, "bouncing_balls_3d", {"--duration", "0.2"});
  ASSERT_EQ(report.engines(), 3u);
  ASSERT_FALSE(report.engine(1).at("supported").get<bool>());
  const Result dom = open_page(dir, chromium, page_url(report, "?t=0"));
  ASSERT_EQ(dom.status, 0) << dom.err;
  expect_no_script_errors(dom);
  const size_t reason = dom.out.find("class=\"replay-reason\"");
  ASSERT_NE(reason, std::string::npos) << dom.out;
  const std::string box = dom.out.substr(reason, dom.out.find("</div>", reason) - reason);
  EXPECT_NE(box.find(">not supported by box2d: 3-D scenes<"), std::string::npos) << box;
  EXPECT_NE(dom.out.find("seen along \u2212z"), std::string::npos);

  const fs::path png = dir / "3d.png";
  const Result r = open_page(dir, chromium, page_url(report, "?t=0"), png);
  ASSERT_EQ(r.status, 0) << r.err;
  const Image image = read_png(png);
  const Layout layout(report);
  const auto [left, top] = layout.canvas_corner(1);
  EXPECT_TRUE(has_colour(image, {left + layout.size / 2, top + layout.size * 0.75}, 1, kReasonBackground)) << "box2d's panel";
  for (size_t k : {size_t{0}, size_t{2}}) {
    size_t nearest = 0;
    for (size_t i = 1; i < report.radius.size(); ++i)
      if (report.position(k, 0, i)[2] > report.position(k, 0, nearest)[2]) nearest = i;
    const auto p = report.position(k, 0, nearest);
    EXPECT_TRUE(has_colour(image, layout.pixel(k, p[0], p[1]), 1, body_colour(nearest)))
        << report.engine(k).at("name") << ", body " << nearest;
  }
}

// Found by an accessibility audit. With JavaScript off the replay showed blank canvases, dead controls
// and an engine's "not run" box. Now all of it is hidden until the script runs: the whole page (a
// window tall enough for it) has no pixel of that box when the replay's scripts do not run (a copy of
// the page without its <script> tags: headless Chromium takes no picture with JavaScript off), and
// has it when they do.
TEST_F(ReplayBrowser, WithoutJavaScriptThePanelsAreNotShown) {
  TempDir dir;
  const Report report = make_report(dir, "bouncing_balls_3d", {"--duration", "0.2"});
  ASSERT_FALSE(report.engine(1).at("supported").get<bool>());
  auto reason_pixels = [&](bool javascript) {
    const fs::path png = dir / (javascript ? "with.png" : "without.png");
    // (Both copies without the pictures of the first and last frames, whose Box2D panel, drawn by
    // render/, may be near the colour looked for.)
    std::string html = read_file(report.folder / "index.html");
    std::vector<std::string> tags = {"<img src=\"first_and_last.png\" alt=\"every engine at the first and the last instant\">"};
    if (!javascript) tags.insert(tags.end(), {"<script src=\"replay-data.js\"></script>", "<script src=\"replay.js\"></script>"});
    for (const std::string& tag : tags) {
      const size_t at = html.find(tag);
      EXPECT_NE(at, std::string::npos) << tag;
      if (at != std::string::npos) html.erase(at, tag.size());
    }
    const fs::path copy = report.folder / (javascript ? "with-script.html" : "no-script.html");
    std::ofstream(copy, std::ios::binary) << html;
    const Result r = open_page(dir, chromium, "file://" + fs::absolute(copy).string(), png, 1, 4000);
    EXPECT_EQ(r.status, 0) << r.err;
    const Image image = read_png(png);
    long n = 0;
    for (size_t at = 0; at + 2 < image.rgb.size(); at += 3) {
      bool close = true;
      // (within 2: a flat fill; the tables' headers, #f3f3f3, are within 8 of it)
      for (int c = 0; c < 3; ++c) close = close && std::abs(image.rgb[at + c] - kReasonBackground[c]) <= 2;
      n += close;
    }
    return n;
  };
  EXPECT_GT(reason_pixels(true), 200 * 200) << "with JavaScript, Box2D's panel says why it did not run";
  // (Not one row of the 288 px box: a few pixels of antialiased text elsewhere can be of that colour.)
  EXPECT_LT(reason_pixels(false), 288) << "without the replay's scripts";
}

// Found by an accessibility audit: the canvases had no name and the slider said only its frame
// number. After the script, each canvas (role="img") is named by its engine, the time and the energy
// error shown, and the slider's aria-valuetext is the time.
TEST_F(ReplayBrowser, TheSliderAndEveryPictureSayWhatTheyShow) {
  TempDir dir;
  const Report report = make_report(dir, "head_on");
  const Result r = open_page(dir, chromium, page_url(report, "#t=1.0"));
  ASSERT_EQ(r.status, 0) << r.err;
  expect_no_script_errors(r);
  const std::string time = shown_time(report.engine(0).at("t"), 1.0);
  EXPECT_NE(r.out.find("aria-valuetext=\"" + std::string(time) + "\""), std::string::npos) << time << "\n" << r.out;
  for (size_t k = 0; k < report.engines(); ++k) {
    const std::string label = "aria-label=\"" + report.engine(k).at("name").get<std::string>() + " at " + time + ", \u0394E/E\u2080 = ";
    EXPECT_EQ(occurrences(r.out, label), 1u) << label << "\n" << r.out;
  }
  // The script has shown what it drives.
  for (const char* shown : {"<div class=\"replay-panels\">", "<div class=\"replay-controls\">", "<p class=\"replay-notes\">"})
    EXPECT_NE(r.out.find(shown), std::string::npos) << shown << "\n" << r.out;
}

// Found by an accessibility audit: space and the arrows were the replay's wherever the focus was,
// whenever the replay was on screen (space no longer scrolled the page). Now only with the focus in
// the replay. A copy of the page dispatches the keys from a script of its own, once the replay's has
// run, and writes down the replay's clock and whether the key's default (scrolling) was prevented.
TEST_F(ReplayBrowser, KeysActOnlyWithTheFocusInTheReplay) {
  TempDir dir;
  const Report report = make_report(dir, "head_on");
  std::string html = read_file(report.folder / "index.html");
  const size_t end = html.rfind("</body>");
  ASSERT_NE(end, std::string::npos);
  html.insert(end, R"(<script>
window.addEventListener("load", () => {
  const section = document.getElementById("replay"), clock = section.querySelector(".replay-clock");
  const key = (target, name) => {
    const event = new KeyboardEvent("keydown", {key: name, bubbles: true, cancelable: true});
    target.dispatchEvent(event);
    return (event.defaultPrevented ? "prevented " : "") + clock.textContent;
  };
  document.body.focus();
  const outside = [key(document.body, "ArrowRight"), key(document.body, " ")];
  section.focus();
  const inside = [document.activeElement === section ? "focused" : "not focused", key(section, "ArrowRight")];
  document.body.setAttribute("data-keys", JSON.stringify({outside, inside}));
});
</script>
)");
  {
    std::ofstream out(report.folder / "keys.html", std::ios::binary);
    out << html;
  }
  const Result r = open_page(dir, chromium, "file://" + fs::absolute(report.folder / "keys.html").string() + "?t=0");
  ASSERT_EQ(r.status, 0) << r.err;
  expect_no_script_errors(r);
  const size_t at = r.out.find("data-keys=\"");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string escaped = r.out.substr(at + 11, r.out.find('"', at + 11) - at - 11);
  std::string text;  // (the attribute's &quot; back to ")
  for (size_t i = 0; i < escaped.size(); ++i) {
    const bool quote = escaped.compare(i, 6, "&quot;") == 0;
    text += quote ? '"' : escaped[i];
    if (quote) i += 5;
  }
  const auto keys = nlohmann::json::parse(text);
  const std::string frames = " of " + std::to_string(report.engine(0).at("t").size());
  EXPECT_NE(keys["outside"][0].get<std::string>().find("frame 1" + frames), std::string::npos) << keys;
  EXPECT_EQ(keys["outside"][0].get<std::string>().rfind("prevented", 0), std::string::npos) << keys;
  EXPECT_EQ(keys["outside"][1].get<std::string>().rfind("prevented", 0), std::string::npos) << "space scrolls: " << keys;
  EXPECT_EQ(keys["inside"][0], "focused") << keys;
  EXPECT_NE(keys["inside"][1].get<std::string>().find("prevented "), std::string::npos) << keys;
  EXPECT_NE(keys["inside"][1].get<std::string>().find("frame 2" + frames), std::string::npos) << keys;
}

}  // namespace
