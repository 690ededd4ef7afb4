// render/: pixels where the projection formula puts them, the sizes asked for, the same bytes for the same
// input, and the `motus render` command's failures as a user meets them (exit 2, one line).
//   Pixel positions come from the camera formulas stated in render/motus/render/camera.hpp (restated below);
//   colours from render::body_color and DrawOptions::background, which the drawing uses unchanged inside a
//   disc and away from everything.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <span>
#include <sstream>
#include <numeric>
#include <string>
#include <vector>

#include "motus/render/canvas.hpp"
#include "motus/render/compose.hpp"
#include "motus/render/draw.hpp"
#include "motus/render/draw_primitives.hpp"
#include "motus/render/image.hpp"
#include "motus/render/text.hpp"
#include "motus/render/video.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace fs = std::filesystem;
using namespace motus;
using namespace motus::render;

#include "cli_harness.hpp"

namespace {

using namespace motus_test;

// One 2-D ball of radius r at (x, y), nothing else.
SceneDescription one_ball(int dimensions, std::vector<double> position, double radius) {
  SceneDescription scene;
  scene.name = "one_ball";
  MechanicalDescription m;
  m.dimensions = dimensions;
  BodyDescription body;
  body.radius = radius;
  body.position = position;
  body.velocity.assign(position.size(), 0.0);
  m.bodies.push_back(body);
  scene.mechanical = m;
  return scene;
}

}  // namespace

// Orthographic camera (camera.hpp): px = v.x + v.width/2 + (x − center_x)·scale, py = v.y + v.height/2 − (y − center_y)·scale.
// A 200 × 160 canvas, center (0, 0), scale 40 px/m, ball of radius 0.5 m at (1, 0.5):
//   px = 100 + 1·40 = 140, py = 80 − 0.5·40 = 60, radius 0.5·40 = 20 px.
// Pixel (140, 60) covers [140, 141) × [60, 61): deep inside the disc, so every supersample is the ball's colour.
// Pixel (140 + 20 + 3, 60) is 3 px beyond the edge: the background, untouched.
TEST(RenderPixels, BallLandsWhereTheOrthographicFormulaSays) {
  Canvas canvas(200, 160, 2);
  const SceneDescription scene = one_ball(2, {1.0, 0.5}, 0.5);
  const Camera camera = Camera::orthographic(0, 0, 40);
  const Viewport view = canvas.full();
  const Vec3 p = project(camera, view, {1.0, 0.5, 0});
  EXPECT_DOUBLE_EQ(p[0], 140.0);
  EXPECT_DOUBLE_EQ(p[1], 60.0);

  DrawOptions options;
  canvas.clear(options.background);
  const std::vector<double> x{1.0, 0.5};
  draw_mechanical(canvas, view, scene, {x, {}, {}}, camera, options);
  const Image image = canvas.image();
  EXPECT_EQ(image.pixel(140, 60), body_color(0));
  EXPECT_EQ(image.pixel(140 + 20 + 3, 60), options.background);
  EXPECT_EQ(image.pixel(140 - 20 - 3, 60), options.background);
  EXPECT_EQ(image.pixel(140, 60 - 20 - 3), options.background);
  EXPECT_EQ(image.pixel(140, 60 + 20 + 3), options.background);
  // Just inside the rim on each side is still the ball (not background).
  EXPECT_NE(image.pixel(140 + 16, 60), options.background);
  EXPECT_NE(image.pixel(140, 60 + 16), options.background);
}

// Found by an audit of the pictures: a trail joined the frames' positions with straight lines, so at
// a low --fps it cut across every bounce. motus render now records the steps between frames for
// trails, and a trail spans trail_frames frames' time, whatever the states recorded in it: here a
// ball at x = t m, recorded ten times a frame (frames 1 s apart), drawn at t = 3 s with a trail of
// two frames, trails from x = 1 m. (By count, the last two states, it reached back to x = 2.8 m only.)
// Orthographic, center (2, 0), 40 px/m on 200 × 160: x = 1.5 m is pixel 100 + (1.5 − 2)·40 = 80, y = 0 is row 80.
TEST(RenderPixels, ATrailSpansItsFramesTimeThroughEveryStateRecorded) {
  Canvas canvas(200, 160, 2);
  const SceneDescription scene = one_ball(2, {0.0, 0.0}, 0.05);
  Recording rec;
  for (int k = 0; k <= 30; ++k) {
    const double t = k / 10.0;
    const std::vector<double> state{t, 0.0, 1.0, 0.0};
    rec.add(t, state);
  }
  DrawOptions options;
  options.trails = true;
  options.trail_frames = 2;
  options.frame_interval = 1;
  options.overlay = false;
  const Camera camera = Camera::orthographic(2, 0, 40);
  draw_frame(canvas, canvas.full(), scene, rec, 30, camera, options, "");
  const Image image = canvas.image();
  EXPECT_NE(image.pixel(80, 80), options.background) << "the trail at x = 1.5 m";
  EXPECT_EQ(image.pixel(30, 80), options.background) << "nothing before x = 1 m (x = 0.25 m)";
}

// A first-order scene's chart: each variable over its largest size. One that goes below 0 is
// drawn on a −1 … 1 axis: its line stays inside the plot (whose bottom is 40 px above the
// frame's), never below it and off the picture.
TEST(RenderPixels, ATimeSeriesThatGoesNegativeStaysInsideThePlot) {
  Canvas canvas(640, 480, 2);
  const Viewport view = canvas.full();
  DrawOptions options;
  canvas.clear(options.background);
  Recording rec;
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.1 * i, y = std::cos(t);  // from 1 down to −1 and back
    rec.add(t, std::span<const double>(&y, 1));
  }
  draw_time_series(canvas, view, rec, rec.size() - 1, {{"x"}, {}, "s"}, options);
  const Image image = canvas.image();
  int lowest = -1;  // the lowest row the line reaches
  for (int y = 0; y < image.height; ++y)
    for (int x = 48; x < 400; ++x)
      if (image.pixel(x, y) == body_color(0)) lowest = y;
  ASSERT_GE(lowest, 0) << "no line drawn";
  EXPECT_LE(lowest, 480 - 40 + 3) << "the line runs below the plot";  // (its 2.2 px width)
  EXPECT_GE(lowest, 480 - 40 - 3) << "−1 is not at the plot's bottom";
}

// Found by a render-performance audit: text anchored off the canvas (a chart's legend below a small
// frame) was never cleared with its area, so each frame drew every earlier frame's legend again:
// world2 at --size 160x120 took 6 ms for its first frame and 100 ms for its 200th. Clearing an area
// clears the text anchored off the canvas next to it too.
TEST(RenderText, TextAnchoredOffTheCanvasIsClearedWithTheAreaNextToIt) {
  Canvas canvas(200, 50, 1);
  const Color white{255, 255, 255, 255};
  for (int frame = 0; frame < 5; ++frame) {
    canvas.clear(canvas.full(), white);
    canvas.text(5, 30, "inside", {12, {0, 0, 0, 255}});
    canvas.text(5, 70, "below the canvas", {12, {0, 0, 0, 255}});
    canvas.text(-20, 30, "left of it", {12, {0, 0, 0, 255}});
    EXPECT_EQ(canvas.queued_texts(), 3u) << "frame " << frame;
  }
}

// The same in a viewport (a panel) offset into a larger canvas: everything moves by the viewport's corner.
TEST(RenderPixels, ViewportOffsetsTheDrawing) {
  Canvas canvas(400, 160, 2);
  const SceneDescription scene = one_ball(2, {1.0, 0.5}, 0.5);
  const Camera camera = Camera::orthographic(0, 0, 40);
  const Viewport right{200, 0, 200, 160};
  DrawOptions options;
  canvas.clear({255, 255, 255, 255});
  canvas.clear(right, options.background);
  const std::vector<double> x{1.0, 0.5};
  draw_mechanical(canvas, right, scene, {x, {}, {}}, camera, options);
  const Image image = canvas.image();
  EXPECT_EQ(image.pixel(200 + 140, 60), body_color(0));
  EXPECT_EQ(image.pixel(140, 60), (Color{255, 255, 255, 255}));  // the left panel is untouched
}

// Perspective camera (camera.hpp): with f = (target − eye)/|…|, r = f × up, u = r × f, d = p − eye and
// k = (height/2)/tan(fov/2): px = width/2 + k (d·r)/(d·f), py = height/2 − k (d·u)/(d·f).
// Eye (0, 0, 10) looking at the origin, fov 40°, a 200 × 200 canvas: a sphere of radius 1 at (2, 1, 0) has
// d = (2, 1, −10), f = (0, 0, −1), r = (1, 0, 0), u = (0, 1, 0), k = 100/tan 20° = 274.75:
//   px = 100 + 274.75·2/10 = 154.95, py = 100 − 274.75·1/10 = 72.52; its silhouette's radius is about
//   k·1/10 = 27.5 px. The centre pixel is lit (not background); 1.4 radii out is background.
TEST(RenderPixels, SphereLandsWhereThePerspectiveFormulaSays) {
  Canvas canvas(200, 200, 2);
  const SceneDescription scene = one_ball(3, {2, 1, 0}, 1);
  const Camera camera = Camera::perspective({0, 0, 10}, {0, 0, 0}, {0, 1, 0}, 40);
  const double k = 100 / std::tan(20 * std::numbers::pi / 180);
  const Vec3 p = project(camera, canvas.full(), {2, 1, 0});
  EXPECT_NEAR(p[0], 100 + k * 2 / 10, 1e-9);
  EXPECT_NEAR(p[1], 100 - k * 1 / 10, 1e-9);
  DrawOptions options;
  options.ground_grid = false;
  canvas.clear(options.background);
  const std::vector<double> x{2, 1, 0};
  draw_mechanical(canvas, canvas.full(), scene, {x, {}, {}}, camera, options);
  const Image image = canvas.image();
  const int cx = static_cast<int>(p[0]), cy = static_cast<int>(p[1]);
  const double radius = k / 10;
  EXPECT_NE(image.pixel(cx, cy), options.background);
  const Color centre = image.pixel(cx, cy);
  EXPECT_GT(centre.b, centre.r);  // body_color(0) is blue, lit
  EXPECT_EQ(image.pixel(cx + static_cast<int>(1.4 * radius), cy), options.background);
  EXPECT_EQ(image.pixel(cx, cy - static_cast<int>(1.4 * radius)), options.background);
}

TEST(RenderImage, HasTheRequestedSize) {
  Canvas canvas(317, 211, 2);
  const Image image = canvas.image();
  EXPECT_EQ(image.width, 317);
  EXPECT_EQ(image.height, 211);
  EXPECT_EQ(image.rgba.size(), 317u * 211u * 4u);
  TempDir dir;
  write_png((dir / "a.png").string(), image);
  const Image back = read_png((dir / "a.png").string());
  EXPECT_EQ(back.width, 317);
  EXPECT_EQ(back.height, 211);
  EXPECT_EQ(back.rgba, image.rgba);
}

// The first row of the image is the top of the picture (OSMesa's buffer is bottom-up): a ball drawn near
// the top of the world lands in the image's top half.
TEST(RenderImage, RowsAreFlippedToTopDown) {
  Canvas canvas(100, 100, 1);
  const SceneDescription scene = one_ball(2, {0, 1}, 0.1);  // py = 50 − 1·40 = 10
  DrawOptions options;
  canvas.clear(options.background);
  const std::vector<double> x{0, 1};
  draw_mechanical(canvas, canvas.full(), scene, {x, {}, {}}, Camera::orthographic(0, 0, 40), options);
  const Image image = canvas.image();
  EXPECT_EQ(image.pixel(50, 10), body_color(0));
  EXPECT_EQ(image.pixel(50, 89), options.background);
}

TEST(RenderImage, SameInputGivesTheSameBytes) {
  TempDir dir;
  const SceneDescription scene = load_scene(kScenes + "/bouncing_balls.json");
  Recording recording;
  std::vector<double> state;
  for (const auto& b : scene.mechanical->bodies) state.insert(state.end(), b.position.begin(), b.position.end());
  for (const auto& b : scene.mechanical->bodies) state.insert(state.end(), b.velocity.begin(), b.velocity.end());
  recording.add(0, state, 1.0);
  for (const char* name : {"a.png", "b.png"}) {
    Canvas canvas(320, 240, 2);
    const Camera camera = fit_camera(scene, recording, canvas.full());
    DrawOptions options;
    options.velocity_arrows = true;
    draw_frame(canvas, canvas.full(), scene, recording, 0, camera, options, "a note");
    write_png((dir / name).string(), canvas.image());
  }
  const std::string a = read_file(dir / "a.png"), b = read_file(dir / "b.png");
  EXPECT_GT(a.size(), 1000u);
  EXPECT_EQ(a, b);
}

TEST(RenderText, DrawsWithTheDefaultFontAndNamesAMissingOne) {
  Image image(120, 40, {255, 255, 255, 255});
  draw_text(image, 5, 28, "t = 1.00", {20, {0, 0, 0, 255}});
  long dark = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) dark += image.pixel(x, y).r < 128;
  EXPECT_GT(dark, 40);
  EXPECT_GT(text_width("t = 1.00", {20}), 40);
  try {
    Font font("/nonexistent/font.ttf");
    FAIL() << "no error for a missing font";
  } catch (const RenderError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/font.ttf"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("fonts-dejavu-core"), std::string::npos);
  }
}

// Clearing a part of the canvas clears the text queued there too, and only there: a panel drawn
// again kept the overlay of the one before (canvas.hpp promises its queued text goes).
TEST(RenderText, ClearingAnAreaClearsItsQueuedTextOnly) {
  Canvas canvas(200, 50, 1);
  const Color white{255, 255, 255, 255};
  canvas.clear(white);
  canvas.text(5, 30, "MOTUS", {20, {0, 0, 0, 255}});
  canvas.text(105, 30, "MOTUS", {20, {0, 0, 0, 255}});
  canvas.clear(Viewport{0, 0, 100, 50}, white);
  const Image image = canvas.image();
  long left = 0, right = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) (x < 100 ? left : right) += image.pixel(x, y).r < 128;
  EXPECT_EQ(left, 0);
  EXPECT_GT(right, 40);
}

TEST(RenderCompose, SideBySidePanelsWithLabels) {
  const std::vector<Image> panels{Image(100, 80, {255, 0, 0, 255}), Image(100, 80, {0, 0, 255, 255}),
                                  Image(100, 80, {0, 255, 0, 255})};
  ComposeStyle style;
  const Image row = compose_side_by_side(panels, {"motus", "Box2D", "Bullet"}, style);
  const int band = static_cast<int>(std::ceil(style.label_size * 1.7));
  EXPECT_EQ(row.width, 3 * 100 + 4 * style.gap);
  EXPECT_EQ(row.height, 80 + band + 2 * style.gap);
  EXPECT_EQ(row.pixel(style.gap + 50, style.gap + band + 40), (Color{255, 0, 0, 255}));
  EXPECT_EQ(row.pixel(2 * style.gap + 100 + 50, style.gap + band + 40), (Color{0, 0, 255, 255}));
  long ink = 0;  // the labels are drawn in the band above
  for (int x = 0; x < row.width; ++x)
    for (int y = style.gap; y < style.gap + band; ++y) ink += row.pixel(x, y).r < 200;
  EXPECT_GT(ink, 30);
  const Image sheet = contact_sheet(panels, 2);
  EXPECT_EQ(sheet.width, 2 * 100 + 3 * style.gap);
}

// ---------------------------------------------------------------------------------------------------------
// The command as a user runs it.

TEST(RenderCommand, WritesFramesAtTheRateAskedOfTheSizeAsked) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string(), "--size", "160x120",
                                     "--fps", "4", "--duration", "1", "--set", "dt=0.05"});
  ASSERT_EQ(r.status, 0) << r.err;
  for (int k = 0; k <= 4; ++k) {  // t = 0, 0.25, 0.5, 0.75, 1
    const fs::path frame = dir / ("frames/frame_0000" + std::to_string(k) + ".png");
    ASSERT_TRUE(fs::exists(frame)) << frame;
    const Image image = read_png(frame.string());
    EXPECT_EQ(image.width, 160);
    EXPECT_EQ(image.height, 120);
  }
  EXPECT_FALSE(fs::exists(dir / "frames/frame_00005.png"));
}

// The default frame rate is at most one frame a step of a fixed-step integrator: World2 (dt = 0.2 years)
// drew 30 frames a simulated year, 6 of each state, and spring (dt = 1 s) 30 of each. Now a frame every
// dt, so floor(T/dt) + 1 frames, each a new step: no frame's bytes are the frame before's.
namespace {
std::string frame_name(long k) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%05ld.png", k);
  return name;
}
std::string as_g(double x, int digits = 6) {  // printf's %g (%.3g: digits 3), as the summary writes numbers
  char text[32];
  std::snprintf(text, sizeof text, "%.*g", digits, x);
  return text;
}
}  // namespace

TEST(RenderCommand, ByDefaultEveryFrameIsANewStep) {
  TempDir dir;
  for (const auto& [name, years] : std::vector<std::pair<std::string, double>>{{"world2", 2.0}, {"spring", 5.0}}) {
    const double dt = load_scene(kScenes + "/" + name + ".json").dt;
    ASSERT_GT(dt, 1.0 / 30) << name << ": the scene no longer has a step longer than a default frame";
    const long expected = static_cast<long>(std::floor(years / dt + 1e-9)) + 1;  // world2: 11, spring: 6
    const fs::path out = dir / name;
    const auto r = run_motus(dir, {"render", name, "--out", out.string(), "--size", "320x240", "--duration",
                                   as_g(years)});
    ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    EXPECT_EQ(r.err, "") << name;
    EXPECT_EQ(r.out.rfind(std::to_string(expected) + " frames of 320x240 at " + as_g(1 / dt) + " per simulated", 0), 0u)
        << r.out;
    EXPECT_NE(r.out.find("one a step"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out / frame_name(expected))) << name;
    std::string before;
    for (long k = 0; k < expected; ++k) {
      const std::string frame = read_file(out / frame_name(k));
      ASSERT_FALSE(frame.empty()) << name << " frame " << k;
      EXPECT_NE(frame, before) << name << ": frame " << k << " repeats the one before";
      before = frame;
    }
  }
}

// An --fps above one frame a step is drawn as asked (a video at a round rate may be wanted), and said in
// one line before the drawing: World2 over 2 years at 30 a year is 61 frames of 2/0.2 + 1 = 11 states.
TEST(RenderCommand, AnFpsAboveOneFrameAStepIsSaidInOneLine) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "world2", "--out", (dir / "frames").string(), "--size", "64x48", "--fps", "30",
                                 "--duration", "2"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("motus: note: --fps 30 is more than one frame a step of world2 (dt = 0.2 years): 11 of the 61 "
                        "frames differ",
                        0),
            0u)
      << r.err;
  EXPECT_NE(r.err.find("(--fps 5 draws each step once)"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.rfind("61 frames (11 distinct) of 64x48 at 30 per simulated year", 0), 0u) << r.out;
  EXPECT_TRUE(fs::exists(dir / "frames/frame_00060.png"));
}

// A video of a run shorter than one step, at the default of one frame a step, has one frame: refused up
// front as the --duration's (no --fps was given to name), one line, exit 2. (At 30 frames a second it drew
// spring's one state at t = 1 s, past the 0.5 s asked for, 15 times.)
TEST(RenderCommand, AVideoShorterThanAStepAtTheDefaultRateIsRefusedInOneLine) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string(), "--size", "64x48", "--duration",
                                 "0.5", "--video", "gif"});  // (refused before ffmpeg is looked for)
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--duration: a video needs two frames, and a 0.5 s run at one frame a step (dt = 1 s) has one"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir / "frames"));
}

namespace {
// The frame delays (hundredths of a second) of a GIF: each Graphic Control Extension's (21 F9 04, four
// bytes, a 00 terminator).
std::vector<int> gif_delays(const std::string& gif) {
  std::vector<int> delays;
  for (size_t at = 0; at + 8 <= gif.size(); ++at)
    if (static_cast<unsigned char>(gif[at]) == 0x21 && static_cast<unsigned char>(gif[at + 1]) == 0xF9 &&
        gif[at + 2] == 4 && gif[at + 7] == 0)
      delays.push_back(static_cast<unsigned char>(gif[at + 4]) | static_cast<unsigned char>(gif[at + 5]) << 8);
  return delays;
}
}  // namespace

// The video plays at the frame rate, so a simulated year takes a second to watch at the default's
// one frame a step as it did at 30 a year: World2's frames, dt = 0.2 years apart, last 20 hundredths
// of a second each (they were 31 frames of 3–4 hundredths, six of each state).
TEST(RenderCommand, AVideoAtOneFrameAStepPlaysASimulatedYearInASecond) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "world2", "--out", (dir / "frames").string(), "--size", "64x48", "--duration",
                                 "1", "--video", "gif"});
  if (r.status == 2 && r.err.find("ffmpeg not found") != std::string::npos) GTEST_SKIP() << "no ffmpeg here";
  ASSERT_EQ(r.status, 0) << r.err;
  const double dt = load_scene(kScenes + "/world2.json").dt;
  const std::vector<int> delays = gif_delays(read_file(dir / "frames/world2.gif"));
  EXPECT_EQ(delays.size(), 6u);  // 1/0.2 + 1 frames
  for (int delay : delays) EXPECT_EQ(delay, static_cast<int>(std::lround(100 * dt)));
}

// A run longer than 20 s plays faster by default, in 20 s of video at 30 frames a second: thomas's
// 500 s drew 10,001 frames at one a step (393 MB, two and a half minutes) for an eight-minute video
// of a slowly growing curve. Over 100 s it plays at 100/20 = 5 s a second, 30/5 = 6 frames a
// simulated second (dt = 0.05 is no limit), 100·6 + 1 frames; the GIF's delays (hundredths) add up
// to their count over 30 a second, to the rounding of each (at most half a hundredth).
TEST(RenderCommand, ARunLongerThanTwentySecondsPlaysInTwentyByDefault) {
  TempDir dir;
  const SceneDescription thomas = load_scene(kScenes + "/thomas.json");
  ASSERT_GT(thomas.duration, 20);  // (the default here is about the scene's own, longer run)
  const auto r = run_motus(dir, {"render", "thomas", "--out", (dir / "frames").string(), "--size", "32x24", "--duration",
                                 "100", "--video", "gif"});
  if (r.status == 2 && r.err.find("ffmpeg not found") != std::string::npos) GTEST_SKIP() << "no ffmpeg here";
  ASSERT_EQ(r.status, 0) << r.err;
  const long frames = 100 * 6 + 1;
  EXPECT_EQ(r.out.rfind(std::to_string(frames) + " frames of 32x24 at 6 per simulated second (100 s of thomas, played "
                        "at 5 s a second)", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("video        " + (dir / "frames" / "thomas.gif").string() + ": " + as_g(frames / 30.0, 3) +
                       " s at 30 frames a second"), std::string::npos) << r.out;
  const std::vector<int> delays = gif_delays(read_file(dir / "frames/thomas.gif"));
  ASSERT_EQ(delays.size(), static_cast<size_t>(frames));
  const int total = std::accumulate(delays.begin(), delays.end(), 0);
  EXPECT_NEAR(total, 100.0 * frames / 30, 0.5 * frames / 30.0 + 1) << total;
  // --speed 1 gives the old one a second back: 1/dt = 20 frames a simulated second at most.
  const auto one = run_motus(dir, {"render", "thomas", "--out", (dir / "one").string(), "--size", "32x24", "--duration",
                                   "21", "--speed", "1"});
  ASSERT_EQ(one.status, 0) << one.err;
  EXPECT_EQ(one.out.rfind(std::to_string(21 * 20 + 1) + " frames of 32x24 at 20 per simulated second, one a step (21 s "
                          "of thomas) in", 0), 0u) << one.out;
}

// --speed: simulated seconds a second of video. Below 1 the frames come closer in simulated time
// (30/0.5 = 60 a second; bouncing_balls' dt = 0.01 allows 100), and the video's rate is fps × speed,
// which a GIF's hundredths limit to 50; bad values are one line, exit 2.
TEST(RenderCommand, SpeedSetsTheSimulatedTimeASecondOfVideoShows) {
  TempDir dir;
  const auto slow = run_motus(dir, {"render", "bouncing_balls", "--out", (dir / "slow").string(), "--size", "32x24",
                                    "--duration", "1", "--speed", "0.5"});
  ASSERT_EQ(slow.status, 0) << slow.err;
  EXPECT_EQ(slow.out.rfind("61 frames of 32x24 at 60 per simulated second (1 s of bouncing_balls, played at 0.5 s a "
                           "second)", 0), 0u) << slow.out;
  const auto gif = run_motus(dir, {"render", "bouncing_balls", "--out", (dir / "gif").string(), "--fps", "40", "--speed",
                                   "2", "--video", "gif"});
  EXPECT_EQ(gif.status, 2);
  EXPECT_EQ(gif.err, "motus: error: --fps/--speed: a GIF plays at most 50 frames per second (its frame delay is in "
                     "hundredths of a second), not 80 (40 a simulated second × 2 s a second): a lower --fps or --speed, "
                     "or --video mp4\n");
  for (const std::string bad : {"0", "-1", "nan", "inf"}) {
    const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "bad").string(), "--speed", bad});
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir / "bad"));
  }
}

// The time axis's labels keep apart: World2 over one year ticked every 0.1 year, 34 px apart, under
// labels such as "1900.1" 36 px wide — "19001900.11900.2…1901" on the frame. The band the tick labels
// are drawn in (baselines at the plot's bottom + 15 px, the bottom 40 px above the frame's:
// draw_time_series.cpp) is cut into runs of inked columns; each run must be one label at most as wide
// as the widest label could be, and the runs a space apart at least.
TEST(RenderPixels, TimeAxisLabelsStayApartOverAShortRun) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "world2", "--out", (dir / "frames").string(), "--size", "640x480", "--fps", "5",
                                 "--duration", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  const Image frame = read_png((dir / "frames/frame_00005.png").string());
  const Color background = DrawOptions{}.background;
  const int baseline = frame.height - 40 + 15;
  const TextStyle tick{11};
  int widest = 0;
  for (int i = 0; i <= 10; ++i) widest = std::max(widest, text_width(as_g(1900 + 0.1 * i), tick));
  const int space = text_width(" ", tick);
  ASSERT_GT(widest, 20);
  std::vector<std::pair<int, int>> runs;  // [first, last] inked column
  int blank = space;                      // blank columns since the last inked one
  for (int x = 0; x < frame.width; ++x) {
    bool inked = false;
    for (int y = baseline - 10; y <= baseline + 3; ++y) inked = inked || frame.pixel(x, y) != background;
    if (!inked) {
      ++blank;
      continue;
    }
    if (blank >= 2 || runs.empty()) runs.push_back({x, x});  // (two blank columns: between digits there are fewer)
    runs.back().second = x;
    blank = 0;
  }
  EXPECT_GE(runs.size(), 3u) << "fewer than three labels stand apart on the axis";
  for (size_t i = 0; i < runs.size(); ++i) {
    EXPECT_LE(runs[i].second - runs[i].first + 1, widest) << "labels run into each other at x = " << runs[i].first;
    if (i > 0) {
      EXPECT_GE(runs[i].first - runs[i - 1].second - 1, space) << "labels closer than a space at x = " << runs[i].first;
    }
  }
}

// Found by fuzzing the options: --trails and --arrows on a first-order system drew nothing and
// said nothing (the frames were those of a render without them). They are said not to be drawn.
TEST(RenderCommand, TrailsAndArrowsOnAFirstOrderSystemAreSaidNotDrawn) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "lorenz", "--out", (dir / "frames").string(), "--size", "64x48", "--fps", "4",
                                 "--duration", "0.5", "--trails", "--arrows"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("trails/arrows none drawn: --trails and --arrows draw bodies"), std::string::npos) << r.out;
}

TEST(RenderCommand, NeverOverwritesAFolderUnlessAsked) {
  TempDir dir;
  fs::create_directories(dir / "frames");
  auto r = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string(), "--duration", "0"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--overwrite"), std::string::npos) << r.err;
  r = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string(), "--duration", "0", "--overwrite"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "frames/frame_00000.png"));
}

// "--out a/r/" (a shell's completion adds the slash) is the folder a/r: render made it as its own
// parent's child, then found it "already exists (made meanwhile, by another run?)", exit 2, and
// left a/r behind; grade --batch said "results in gb//".
TEST(RenderCommand, AFolderNamedWithATrailingSlashIsThatFolder) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "a/r").string() + "/", "--size", "64x48",
                                 "--duration", "0.2"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "a/r/frame_00000.png"));
  EXPECT_NE(r.out.find((dir / "a/r").string() + "/ ("), std::string::npos) << r.out;  // (not "a/r//")
}

// A render into folders it makes (a/r, both new) that fills the disk removes what it made, the
// folders too, and names the frame where it was to be. It removed r with its frames, then stopped
// at r being gone already, and left a/ (checked by hand at stop 44; here on a 256 kB file system of
// its own, in a private mount namespace, as root).
TEST(RenderCommand, ARenderThatFillsTheDiskLeavesNothingOfItsOwn) {
  TempDir dir;
  fs::create_directories(dir / "small");
  // (dt = 0.01: 91 frames at 30 a second, more than 256 KB; at the scene's dt = 1 s it is 4 frames a step apart, which fit)
  const std::string script = "mount -t tmpfs -o size=256k tmpfs \"$1\" && exec \"$2\" render spring --out \"$1/a/r\" "
                             "--size 320x240 --duration 3 --set dt=0.01";
  const auto r = run_program(dir, "/usr/bin/unshare",
                             {"--mount", "--propagation", "private", "/bin/sh", "-c", script + "; s=$?; ls -A \"$1\"; exit $s",
                              "sh", (dir / "small").string(), kMotus});
  // (unshare itself failing — in a chroot, whose root is no mount point — is no private mount either)
  if ((r.status != 1 && r.err.find("mount") != std::string::npos) || r.err.rfind("unshare: ", 0) == 0)
    GTEST_SKIP() << "no private mounts here: " << r.err;
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find((dir / "small/a/r/frame_").string()), std::string::npos) << r.err;  // (not the partial folder)
  EXPECT_EQ(r.out, "") << "left on the full disk: " << r.out;
}

TEST(RenderCommand, ImpossibleSizeExits2WithOneLine) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string(), "--size", "100000x16"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  // Named as the option (it began "OSMesa could not draw", which cli.md's error format does not allow).
  EXPECT_NE(r.err.find("motus: error: --size: 100000x16 pixels at --supersample 2 is 200000 x 32, past what OSMesa draws"),
            std::string::npos)
      << r.err;
  // And one whose buffer alone would pass 1 GiB.
  const auto big = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string(), "--size", "100000x100000"});
  EXPECT_EQ(big.status, 2);
  EXPECT_EQ(count_lines(big.err), 1) << big.err;
  EXPECT_NE(big.err.find("motus: error: --size: 100000x100000 pixels at --supersample 2 needs an offscreen buffer over 1 GiB"),
            std::string::npos)
      << big.err;
  // Found by fuzzing the options: sides of more than six digits were "expected WIDTHxHEIGHT", and at
  // 999999999 a side the buffer's size overflowed a long and the run failed "out of memory", exit 1.
  for (const std::string size : {"99999999x99999999", "999999999x999999999"}) {
    const auto huge = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string(), "--size", size});
    EXPECT_EQ(huge.status, 2) << huge.err;
    EXPECT_NE(huge.err.find("motus: error: --size: " + size + " pixels at --supersample 2 needs an offscreen buffer over 1 GiB"),
              std::string::npos)
        << huge.err;
  }
  EXPECT_FALSE(fs::exists(dir / "frames"));  // nothing made before the failure
}

TEST(RenderCommand, FailedContextExits2WithOneLine) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string()}, {"MOTUS_RENDER_FAIL_CONTEXT=1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("OSMesa could not create"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("install the Debian package"), std::string::npos) << r.err;  // (it is installed: it answered)
}

TEST(RenderCommand, MissingFfmpegExits2WithOneLine) {
  TempDir dir;
  fs::create_directories(dir / "empty");
  const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string(), "--video", "mp4"},
                           {"PATH=" + (dir / "empty").string()});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("ffmpeg not found on PATH"), std::string::npos) << r.err;
}

// compare --render without ffmpeg still writes its report and pictures; the page says why there
// is no video (only the terminal did).
TEST(RenderCommand, ACompareWithoutFfmpegSaysOnItsPageWhyThereIsNoVideo) {
  TempDir dir;
  fs::create_directories(dir / "empty");
  const auto r = run_motus(dir, {"compare", "head_on", "--render", "--duration", "0.3", "--repeats", "1", "--out",
                                 (dir / "report").string()},
                           {"PATH=" + (dir / "empty").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("video skipped: ffmpeg not found on PATH"), std::string::npos) << r.err;
  EXPECT_NE(read_file(dir / "report/index.html").find("video skipped: ffmpeg not found on PATH"), std::string::npos);
}

TEST(RenderCommand, MissingFontExits2WithOneLine) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string()}, {"MOTUS_FONT=/nonexistent/font.ttf"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("fonts-dejavu-core"), std::string::npos) << r.err;
}

TEST(RenderCommand, AnUnstableRunIsDrawnThenExitsOne) {
  // Euler on x'' = -x at dt = 10 grows by 1 + 100 a step: infinite within a few hundred steps. The
  // frames are drawn (they show it), then exit 1 with one line, as `motus run` does.
  TempDir dir;
  const auto r = run_motus(dir, {"render", "oscillator", "--integrator", "euler", "--set", "dt=10", "--duration", "20000",
                                 "--fps", "0.0001", "--size", "64x48", "--out", (dir / "frames").string()});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("no longer finite"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir / "frames" / "frame_00002.png"));
}

TEST(RenderCommand, APercentSignInTheFolderIsNoPartOfTheVideosPattern) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "p%dq").string(), "--size", "32x32", "--fps", "10",
                                 "--duration", "0.3", "--video", "gif"});
  if (r.status == 2 && r.err.find("ffmpeg not found") != std::string::npos) GTEST_SKIP() << "no ffmpeg here";
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "p%dq" / "spring.gif"));
}

// ffmpeg can report an error and still exit 0 (a disk that fills while it writes the video's
// trailer: the video does not play). Its error is the run's, in one line, exit 1 — not two of
// ffmpeg's lines and "video  …/spring.mp4", exit 0. The ffmpeg here is a stand-in that does so.
TEST(RenderCommand, AnErrorFfmpegReportsFailsTheRunEvenAtExitZero) {
  TempDir dir;
  fs::create_directories(dir / "bin");
  write_file(dir / "bin/ffmpeg", "#!/bin/sh\necho 'Error writing trailer of out.mp4: No space left on device' >&2\n"
                                 "echo 'Error closing file out.mp4: No space left on device' >&2\nexit 0\n");
  fs::permissions(dir / "bin/ffmpeg", fs::perms::owner_all);
  // (dt = 0.1: at the scene's 1 s, --fps 10 is more than one frame a step, and that is said on a line of its own)
  const auto r = run_motus(dir, {"render", "spring", "--out", (dir / "frames").string(), "--size", "32x32", "--fps", "10",
                                 "--duration", "0.3", "--set", "dt=0.1", "--video", "mp4"},
                           {"PATH=" + (dir / "bin").string() + ":/usr/bin:/bin"});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("it said: Error writing trailer of out.mp4: No space left on device"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.find("video"), std::string::npos) << r.out;
}

// The same in compare --render: the video it asked for could not be made, and the report said
// "video skipped" on its page and exit 0, as if ffmpeg were only missing. Now it is a failed run,
// as a picture that cannot be written is: one line naming the video, exit 1, no report folder.
TEST(RenderCommand, ACompareWhoseVideoFfmpegCannotMakeFailsTheRun) {
  TempDir dir;
  fs::create_directories(dir / "bin");
  write_file(dir / "bin/ffmpeg", "#!/bin/sh\necho 'Error writing trailer of out.mp4: No space left on device' >&2\nexit 0\n");
  fs::permissions(dir / "bin/ffmpeg", fs::perms::owner_all);
  const auto r = run_motus(dir, {"compare", "head_on", "--render", "--engines", "motus", "--duration", "0.3", "--fps",
                                 "10", "--size", "64x48", "--repeats", "1", "--out", (dir / "report").string()},
                           {"PATH=" + (dir / "bin").string() + ":/usr/bin:/bin"});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("the video could not be made"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find((dir / "report/comparison.mp4").string()), std::string::npos) << r.err;  // (not the partial name)
  EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "report"));
}

TEST(RenderCommand, GifThroughFfmpeg) {
  TempDir dir;
  const auto r = run_motus(dir, {"render", "newtons_cradle", "--out", (dir / "frames").string(), "--size",
                                     "96x64", "--fps", "5", "--duration", "1", "--video", "gif"});
  if (r.status == 2 && r.err.find("ffmpeg not found") != std::string::npos) GTEST_SKIP() << "no ffmpeg here";
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string gif = read_file(dir / "frames/newtons_cradle.gif");
  ASSERT_GT(gif.size(), 6u);
  EXPECT_EQ(gif.substr(0, 6), "GIF89a");
}

// The camera leaves the scale bar's band free: a body at the bottom of a run's extent (free_fall's
// ball at its start, below where it flies) was drawn half under the bar's box.
TEST(RenderPixels, TheCameraKeepsBodiesAboveTheScaleBar) {
  const SceneDescription scene = one_ball(2, {0.0, 0.0}, 0.5);
  Recording rec;
  for (const double y : {0.0, 5.0}) {  // from the bottom up: (0, 0) is the extent's lowest point
    const std::vector<double> state{0.0, y, 0.0, 0.0};
    rec.add(0.1 * y, state);
  }
  const Viewport view{0, 0, 640, 480};
  const Camera camera = fit_camera(scene, rec, view);
  const double lowest = project(camera, view, {0.0, -0.5, 0})[1];  // the ball's bottom, in pixels down
  // draw_scale_bar: its box's top is 0.9 + 1.5 text sizes above the frame's bottom.
  const double bar_top = 480 - 2.4 * motus::render::detail::overlay_text_size(view);
  EXPECT_LT(lowest, bar_top) << "the ball reaches into the scale bar's box";
}

// A comparison's side-by-side view was fitted to motus's run alone: Bullet's rope, stretched to twice its
// length, ran off the bottom of its panel, under the scale bar (a pictures audit). The shared view takes in
// every engine that ran and stays within kFarthestInView times the first one's reach (half its widest
// extent) of its middle; not one that went farther (a blown-up run would shrink the others to a dot), nor
// one with a position that is not a number, nor one that did not run.
TEST(RenderPixels, ASharedViewTakesInEveryRunThatStaysNearTheFirst) {
  const SceneDescription scene = one_ball(2, {0.0, 0.0}, 0.1);
  auto run_to = [](double y) {  // a ball falling from (0, 0) to (0, y)
    Recording rec;
    for (const double at : {0.0, y}) rec.add(0, std::vector<double>{0.0, at, 0.0, 0.0});
    return rec;
  };
  // The first run reaches y = −2: its middle is y = −1 and its reach 1, so the view may go to y = −5.
  const std::vector<Recording> runs = {run_to(-2), run_to(-4.9), run_to(-5.1), run_to(std::nan("")), run_to(-3)};
  EXPECT_EQ(in_a_shared_view(scene, runs, 0, {true, true, true, true, false}),
            (std::vector<bool>{true, true, false, false, false}));
  // And its camera, fitted to the runs in view, shows the stretched one's lowest point above the scale bar.
  const Recording* both[] = {&runs[0], &runs[1]};
  const Viewport view{0, 0, 640, 480};
  const Camera camera = fit_camera(scene, both, view);
  EXPECT_LT(project(camera, view, {0.0, -4.9 - 0.1, 0})[1], 480 - 2.4 * motus::render::detail::overlay_text_size(view));
}

// Found by a pictures audit: the 3-D camera closed in to 0.9 of the bounding sphere's distance, and
// the box's nearest bottom corner of bouncing_balls_3d, (6, 0, 6), was drawn at y = 503 in a 480 px
// frame (docs/render.md: the camera fits the walls). Every corner of a scene's box is in the frame.
TEST(RenderPixels, TheCameraKeepsEveryCornerOfA3dBoxInTheFrame) {
  const SceneDescription scene = load_scene(kScenes + "/bouncing_balls_3d.json");
  const auto& m = *scene.mechanical;
  ASSERT_FALSE(m.colliders.boxes.empty());
  Recording rec;
  std::vector<double> state;
  for (const auto& b : m.bodies) state.insert(state.end(), b.position.begin(), b.position.begin() + 3);
  for (const auto& b : m.bodies) state.insert(state.end(), b.velocity.begin(), b.velocity.begin() + 3);
  rec.add(0, state);
  for (const Viewport view : {Viewport{0, 0, 640, 480}, Viewport{0, 0, 480, 360}, Viewport{0, 0, 300, 400}}) {
    const Camera camera = fit_camera(scene, rec, view);
    const auto& box = m.colliders.boxes.front();
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner{k & 1 ? box.max[0] : box.min[0], k & 2 ? box.max[1] : box.min[1], k & 4 ? box.max[2] : box.min[2]};
      const Vec3 p = project(camera, view, corner);
      EXPECT_GE(p[0], 0) << view.width << "x" << view.height << ", corner " << k;
      EXPECT_LE(p[0], view.width) << view.width << "x" << view.height << ", corner " << k;
      EXPECT_GE(p[1], 0) << view.width << "x" << view.height << ", corner " << k;
      EXPECT_LE(p[1], view.height) << view.width << "x" << view.height << ", corner " << k;
    }
  }
}

// Every shipped scene draws through the drawing module: its first frame has the size asked
// for and is more than the background (DrawOptions' background colour, unchanged where
// nothing is drawn).
TEST(RenderCommand, DrawsTheFirstFrameOfEveryShippedScene) {
  TempDir dir;
  const Color background = DrawOptions{}.background;
  for (const auto& entry : fs::directory_iterator(kScenes)) {
    if (entry.path().extension() != ".json") continue;
    const std::string name = entry.path().stem().string();
    const fs::path out = dir / name;
    const auto r = run_motus(dir, {"render", name, "--out", out.string(), "--size", "160x120", "--duration", "0"});
    ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    const Image frame = read_png((out / "frame_00000.png").string());
    EXPECT_EQ(frame.width, 160) << name;
    EXPECT_EQ(frame.height, 120) << name;
    long drawn = 0;
    for (int y = 0; y < frame.height; ++y)
      for (int x = 0; x < frame.width; ++x) drawn += frame.pixel(x, y) != background;
    EXPECT_GT(drawn, 200) << name << ": the first frame is (almost) only background";
  }
}

// Commands that draw nothing do not load OpenGL: the dynamic loader's list of what `motus`
// loads (LD_TRACE_LOADED_OBJECTS, what ldd prints) has no libOSMesa and no libLLVM.
TEST(RenderCommand, MotusItselfLoadsNoOpenGL) {
  TempDir dir;
  const auto r = run_motus(dir, {"--version"}, {"LD_TRACE_LOADED_OBJECTS=1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("libstdc++"), std::string::npos) << r.out;  // it did list the libraries
  EXPECT_EQ(r.out.find("OSMesa"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("LLVM"), std::string::npos) << r.out;
}

namespace {
// ffmpeg reads a % in its input as its pattern's: the folder's are doubled. In a folder "q%%" one
// was lost (the escaping moved the name on as it went, and stopped short of the second), and
// `motus render --video` failed after every frame was drawn. Found by an audit of failed writes.
TEST(RenderVideo, AFolderWithPercentSignsGetsItsVideo) {
  TempDir dir;
  const fs::path folder = dir / "q%%";
  fs::create_directories(folder);
  for (int k = 0; k < 2; ++k)
    motus::render::write_png((folder / ("frame_0000" + std::to_string(k) + ".png")).string(), motus::render::Image(32, 32));
  try {
    motus::render::encode_video((folder / "frame_%05d.png").string(), 2, (folder / "v.gif").string(),
                                motus::render::VideoFormat::gif);
  } catch (const RenderError& e) {  // (as the other video tests: no ffmpeg on PATH, nothing to check)
    if (std::string(e.what()).find("ffmpeg not found") != std::string::npos) GTEST_SKIP() << "no ffmpeg here";
    throw;
  }
  EXPECT_EQ(read_file(folder / "v.gif").rfind("GIF89a", 0), 0u);
}
}  // namespace
