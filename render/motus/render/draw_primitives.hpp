#pragma once
// Internal to motus_render (not part of its API; only the draw_*.cpp, overlay.cpp and frame.cpp
// files include it): the colours and drawing helpers every kind of scene shares, and the
// per-dimension drawers that draw_mechanical dispatches to. Everything is in render::detail.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <string>

#include "motus/render/draw.hpp"

namespace motus::render::detail {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kInf = std::numeric_limits<double>::infinity();

struct Box2 {
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  void add(double x, double y, double r = 0) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    x0 = std::min(x0, x - r), y0 = std::min(y0, y - r), x1 = std::max(x1, x + r), y1 = std::max(y1, y + r);
  }
  bool empty() const { return x0 > x1; }
};

struct Box3 {
  Vec3 lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};
  void add(const Vec3& p, double r = 0) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return;
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k] - r), hi[k] = std::max(hi[k], p[k] + r);
  }
  bool empty() const { return lo[0] > hi[0]; }
  Vec3 centre() const { return {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2}; }
  double radius() const {
    const double a = hi[0] - lo[0], b = hi[1] - lo[1], c = hi[2] - lo[2];
    return 0.5 * std::sqrt(a * a + b * b + c * c);
  }
};

// Colours.
Color mix(Color a, Color b, double t);
Color darker(Color c, double f = 0.6);
void gl_color(Color c, double alpha = 1);
// Dark blue → teal → green → yellow (close to viridis), t in [0, 1].
Color time_color(double t);

inline constexpr Color kInk{40, 44, 52, 255};
inline constexpr Color kWall{90, 96, 110, 255};
inline constexpr Color kGround{222, 220, 212, 255};
inline constexpr Color kStick{70, 74, 84, 255};
inline constexpr Color kGrid{200, 200, 196, 255};

// Everything after this draws in canvas pixels (x right, y down) inside the viewport.
void begin_pixels(Canvas& canvas, const Viewport& v);
// Everything after this draws in world coordinates through the camera, with depth testing.
void begin_3d(Canvas& canvas, const Viewport& v, const Camera& cam);

// Shapes in canvas pixels (after begin_pixels).
//
// A filled disc as a triangle fan, with enough sides that the polygon is within 1/8 of
// a supersample of the circle.
void disc(double cx, double cy, double r, Color c, int supersample);
// A ball: a darker rim and the body colour inside.
void ball(double cx, double cy, double r, Color c, int supersample);
// A line of width w pixels as a quad (OpenGL's wide lines vary between drivers).
void thick_line(double x0, double y0, double x1, double y1, double w, Color c, double alpha = 1);
void arrow(double x0, double y0, double x1, double y1, double w, Color c);
// A spring's zig-zag from (x0, y0) to (x1, y1): straight ends, `coils` teeth between.
void zig_zag(double x0, double y0, double x1, double y1, double amplitude, int coils, double w, Color c);

// Body i's point in a plain array of n·d coordinates (zero past d).
Vec3 point_of(std::span<const double> x, int d, int i);
// A round grid step: about range / lines, as 1, 2 or 5 times a power of ten.
double nice_step(double range, int lines);
// The height of the ground: the lowest upward-facing plane, else the bottom of a box.
std::optional<double> ground_height(const MechanicalDescription& m);
// x formatted with a printf format (one double).
std::string format_number(const char* format, double x);
// The overlay's text size for a viewport: 15 px on a 640 × 480 frame, down to 10 px on small ones.
double overlay_text_size(const Viewport& v);

// The mechanical scenes by dimension (draw_1d.cpp, draw_2d.cpp, draw_3d.cpp).
void draw_mechanical_1d(Canvas& canvas, const Viewport& v, const MechanicalDescription& m, const MechanicalFrame& f,
                        const Camera& cam, const DrawOptions& o);
void draw_mechanical_2d(Canvas& canvas, const Viewport& v, const MechanicalDescription& m, const MechanicalFrame& f,
                        const Camera& cam, const DrawOptions& o);
void draw_mechanical_3d(Canvas& canvas, const Viewport& v, const MechanicalDescription& m, const MechanicalFrame& f,
                        const Camera& cam, const DrawOptions& o);

}  // namespace motus::render::detail
