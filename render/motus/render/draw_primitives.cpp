// The shared drawing helpers declared in draw_primitives.hpp (internal to motus_render):
// colours, GL set-up, discs, lines, arrows, zig-zags and small numeric helpers.
#include "motus/render/draw_primitives.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

namespace motus::render::detail {

Color mix(Color a, Color b, double t) {
  auto m = [t](std::uint8_t x, std::uint8_t y) { return static_cast<std::uint8_t>(std::lround(x + (y - x) * t)); };
  return {m(a.r, b.r), m(a.g, b.g), m(a.b, b.b), m(a.a, b.a)};
}

Color darker(Color c, double f) { return mix({0, 0, 0, c.a}, c, f); }

void gl_color(Color c, double alpha) {
  glColor4ub(c.r, c.g, c.b, static_cast<GLubyte>(std::lround(c.a * alpha)));
}

Color time_color(double t) {
  static const Color stops[] = {{68, 1, 84, 255}, {59, 82, 139, 255}, {33, 145, 140, 255}, {94, 201, 98, 255},
                                {253, 231, 37, 255}};
  t = std::clamp(t, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(t));
  return mix(stops[i], stops[i + 1], t - i);
}

void begin_pixels(Canvas& canvas, const Viewport& v) {
  canvas.begin(v);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, v.width, v.height, 0, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glTranslated(-v.x, -v.y, 0);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
}

void begin_3d(Canvas& canvas, const Viewport& v, const Camera& cam) {
  canvas.begin(v);
  const auto P = projection_matrix(cam, v), V = view_matrix(cam);
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(P.data());
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(V.data());
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDisable(GL_BLEND);
}

void disc(double cx, double cy, double r, Color c, int supersample) {
  if (!(r > 0) || !std::isfinite(cx) || !std::isfinite(cy)) return;
  const double rs = r * supersample;
  const int sides = std::clamp(static_cast<int>(std::ceil(kPi / std::acos(std::max(0.0, 1 - 0.125 / rs)))), 8, 128);
  gl_color(c);
  glBegin(GL_TRIANGLE_FAN);
  glVertex2d(cx, cy);
  // The polygon's edges are pushed out so its area matches the circle's.
  const double rr = r / std::sqrt(std::sin(2 * kPi / sides) / (2 * kPi / sides));
  for (int i = 0; i <= sides; ++i) {
    const double a = 2 * kPi * i / sides;
    glVertex2d(cx + rr * std::cos(a), cy + rr * std::sin(a));
  }
  glEnd();
}

void ball(double cx, double cy, double r, Color c, int supersample) {
  if (r >= 3) {
    disc(cx, cy, r, darker(c, 0.7), supersample);
    disc(cx, cy, r - std::clamp(0.08 * r, 1.0, 2.5), c, supersample);
  } else {
    disc(cx, cy, r, c, supersample);
  }
}

void thick_line(double x0, double y0, double x1, double y1, double w, Color c, double alpha) {
  const double dx = x1 - x0, dy = y1 - y0, len = std::hypot(dx, dy);
  if (!(len > 0) || !std::isfinite(len)) return;
  const double nx = -dy / len * w / 2, ny = dx / len * w / 2;
  gl_color(c, alpha);
  glBegin(GL_QUADS);
  glVertex2d(x0 + nx, y0 + ny);
  glVertex2d(x1 + nx, y1 + ny);
  glVertex2d(x1 - nx, y1 - ny);
  glVertex2d(x0 - nx, y0 - ny);
  glEnd();
}

void arrow(double x0, double y0, double x1, double y1, double w, Color c) {
  const double dx = x1 - x0, dy = y1 - y0, len = std::hypot(dx, dy);
  if (!(len > 1) || !std::isfinite(len)) return;
  const double head = std::min(len * 0.4, 4 * w + 4), ux = dx / len, uy = dy / len;
  thick_line(x0, y0, x1 - ux * head * 0.8, y1 - uy * head * 0.8, w, c);
  gl_color(c);
  glBegin(GL_TRIANGLES);
  glVertex2d(x1, y1);
  glVertex2d(x1 - ux * head - uy * head * 0.45, y1 - uy * head + ux * head * 0.45);
  glVertex2d(x1 - ux * head + uy * head * 0.45, y1 - uy * head - ux * head * 0.45);
  glEnd();
}

void zig_zag(double x0, double y0, double x1, double y1, double amplitude, int coils, double w, Color c) {
  const double dx = x1 - x0, dy = y1 - y0, len = std::hypot(dx, dy);
  if (!(len > 0) || !std::isfinite(len)) return;
  const double ux = dx / len, uy = dy / len, nx = -uy, ny = ux;
  const double lead = std::min(0.1 * len, 12.0);
  std::vector<std::array<double, 2>> points{{x0, y0}, {x0 + ux * lead, y0 + uy * lead}};
  const int teeth = 2 * coils;
  for (int i = 1; i < teeth; ++i) {
    const double s = lead + (len - 2 * lead) * i / teeth, side = (i % 2 ? 1 : -1) * amplitude;
    points.push_back({x0 + ux * s + nx * side, y0 + uy * s + ny * side});
  }
  points.push_back({x1 - ux * lead, y1 - uy * lead});
  points.push_back({x1, y1});
  for (size_t i = 1; i < points.size(); ++i) {
    thick_line(points[i - 1][0], points[i - 1][1], points[i][0], points[i][1], w, c);
    disc(points[i][0], points[i][1], w / 2, c, 2);
  }
}

Vec3 point_of(std::span<const double> x, int d, int i) {
  Vec3 p{0, 0, 0};
  for (int k = 0; k < d; ++k) p[static_cast<size_t>(k)] = x[static_cast<size_t>(i * d + k)];
  return p;
}

double nice_step(double range, int lines) {
  const double raw = range / lines, p = std::pow(10, std::floor(std::log10(raw))), m = raw / p;
  return p * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
}

std::optional<double> ground_height(const MechanicalDescription& m) {
  std::optional<double> y;
  for (const auto& p : m.colliders.planes)
    if (p.normal[1] > 0.99) y = std::min(y.value_or(kInf), p.offset / p.normal[1]);
  if (!y)
    for (const auto& b : m.colliders.boxes) y = std::min(y.value_or(kInf), b.min[1]);
  return y;
}

std::string format_number(const char* format, double x) {
  // (printf writes "-nan" or "inf": a label says in words that the run blew up.)
  if (std::isnan(x)) return "not a number";
  if (std::isinf(x)) return x > 0 ? "+infinite" : "-infinite";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, x);
  return buffer;
}

double overlay_text_size(const Viewport& v) { return std::clamp(std::min(1.0 * v.width, 1.4 * v.height) / 36.0, 10.0, 15.0); }

}  // namespace motus::render::detail
