#include "motus/render/draw.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "motus/systems/system_catalog.hpp"

namespace motus::render {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------------------------
// Small helpers

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

Color mix(Color a, Color b, double t) {
  auto m = [t](std::uint8_t x, std::uint8_t y) { return static_cast<std::uint8_t>(std::lround(x + (y - x) * t)); };
  return {m(a.r, b.r), m(a.g, b.g), m(a.b, b.b), m(a.a, b.a)};
}

Color darker(Color c, double f = 0.6) { return mix({0, 0, 0, c.a}, c, f); }

void gl_color(Color c, double alpha = 1) {
  glColor4ub(c.r, c.g, c.b, static_cast<GLubyte>(std::lround(c.a * alpha)));
}

// Dark blue → teal → green → yellow (close to viridis), t in [0, 1].
Color time_color(double t) {
  static const Color stops[] = {{68, 1, 84, 255}, {59, 82, 139, 255}, {33, 145, 140, 255}, {94, 201, 98, 255},
                                {253, 231, 37, 255}};
  t = std::clamp(t, 0.0, 1.0) * 4;
  const int i = std::min(3, static_cast<int>(t));
  return mix(stops[i], stops[i + 1], t - i);
}

const Color kInk{40, 44, 52, 255};
const Color kWall{90, 96, 110, 255};
const Color kGround{222, 220, 212, 255};
const Color kStick{70, 74, 84, 255};
const Color kGrid{200, 200, 196, 255};

// Everything after this draws in canvas pixels (x right, y down) inside the viewport.
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

// A filled disc as a triangle fan, with enough sides that the polygon is within 1/8 of
// a supersample of the circle.
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

// A ball: a darker rim and the body colour inside.
void ball(double cx, double cy, double r, Color c, int supersample) {
  if (r >= 3) {
    disc(cx, cy, r, darker(c, 0.7), supersample);
    disc(cx, cy, r - std::clamp(0.08 * r, 1.0, 2.5), c, supersample);
  } else {
    disc(cx, cy, r, c, supersample);
  }
}

// A line of width w pixels as a quad (OpenGL's wide lines vary between drivers).
void thick_line(double x0, double y0, double x1, double y1, double w, Color c, double alpha = 1) {
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

// A spring's zig-zag from (x0, y0) to (x1, y1): straight ends, `coils` teeth between.
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

// ---------------------------------------------------------------------------------------------------------------
// 2-D

void draw_planes_2d(const MechanicalDescription& m, const Camera& cam, const Viewport& v) {
  const double far = 4.0 * (v.width + v.height);
  for (const auto& plane : m.colliders.planes) {
    const double nx = plane.normal[0], ny = plane.normal[1];
    const Vec3 p = project(cam, v, {nx * plane.offset, ny * plane.offset, 0});
    // In pixels y points down: the normal is (nx, −ny), the wall's direction (ny, nx).
    const double px = nx, py = -ny, tx = ny, ty = nx;
    gl_color(kGround);
    glBegin(GL_QUADS);
    glVertex2d(p[0] + tx * far, p[1] + ty * far);
    glVertex2d(p[0] - tx * far, p[1] - ty * far);
    glVertex2d(p[0] - tx * far - px * far, p[1] - ty * far - py * far);
    glVertex2d(p[0] + tx * far - px * far, p[1] + ty * far - py * far);
    glEnd();
    thick_line(p[0] + tx * far, p[1] + ty * far, p[0] - tx * far, p[1] - ty * far, 2.5, kWall);
  }
}

void draw_boxes_2d(const MechanicalDescription& m, const Camera& cam, const Viewport& v) {
  const double w = 3;
  for (const auto& box : m.colliders.boxes) {
    const Vec3 a = project(cam, v, {box.min[0], box.min[1], 0}), b = project(cam, v, {box.max[0], box.max[1], 0});
    // a is bottom-left, b top-right on screen (y down): the walls go outside the free space.
    const double l = a[0], r = b[0], t = b[1], bo = a[1];
    thick_line(l - w, t - w / 2, r + w, t - w / 2, w, kWall);
    thick_line(l - w, bo + w / 2, r + w, bo + w / 2, w, kWall);
    thick_line(l - w / 2, t - w, l - w / 2, bo + w, w, kWall);
    thick_line(r + w / 2, t - w, r + w / 2, bo + w, w, kWall);
  }
}

void draw_segments_2d(const MechanicalDescription& m, const Camera& cam, const Viewport& v, int ss) {
  for (const auto& s : m.colliders.segments) {
    const Vec3 a = project(cam, v, {s.a[0], s.a[1], 0}), b = project(cam, v, {s.b[0], s.b[1], 0});
    thick_line(a[0], a[1], b[0], b[1], 3, kWall);
    disc(a[0], a[1], 1.5, kWall, ss);
    disc(b[0], b[1], 1.5, kWall, ss);
  }
}

void draw_mechanical_2d(Canvas& canvas, const Viewport& v, const MechanicalDescription& m, const MechanicalFrame& f,
                        const Camera& cam, const DrawOptions& o) {
  const int ss = canvas.supersample(), d = 2, n = static_cast<int>(m.bodies.size());
  begin_pixels(canvas, v);
  draw_planes_2d(m, cam, v);
  draw_boxes_2d(m, cam, v);
  draw_segments_2d(m, cam, v, ss);
  auto at = [&](std::span<const double> x, int i) { return project(cam, v, point_of(x, d, i)); };

  // The central body of an inverse-square field.
  for (const auto& g : m.forces.central_gravity) {
    const Vec3 c = project(cam, v, {g.centre[0], g.centre[1], 0});
    disc(c[0], c[1], 9, {240, 170, 40, 255}, ss);
  }
  if (o.trails && !f.trail.empty() && n <= 64) {
    const size_t count = f.trail.size();
    for (int i = 0; i < n; ++i)
      for (size_t k = 1; k < count; ++k) {
        const Vec3 a = at(f.trail[k - 1], i), b = at(f.trail[k], i);
        thick_line(a[0], a[1], b[0], b[1], 2, body_color(i), 0.15 + 0.6 * static_cast<double>(k) / count);
      }
  }
  for (const auto& s : m.forces.springs) {
    const Vec3 a = at(f.positions, s.a);
    const Vec3 b = s.b >= 0 ? at(f.positions, s.b) : project(cam, v, {s.anchor[0], s.anchor[1], 0});
    zig_zag(b[0], b[1], a[0], a[1], 7, 10, 2, kStick);
  }
  const bool sticks = !m.sticks.empty();
  for (const auto& s : m.sticks) {
    const Vec3 a = at(f.positions, s.a), b = at(f.positions, s.b);
    thick_line(a[0], a[1], b[0], b[1], 2.5, kStick);
  }
  for (int i = 0; i < n; ++i) {
    const Vec3 p = at(f.positions, i);
    const double r = m.bodies[static_cast<size_t>(i)].radius * cam.scale;
    if (r > 0)
      ball(p[0], p[1], r, body_color(i), ss);
    else
      disc(p[0], p[1], sticks ? 3.5 : 6, sticks ? kInk : body_color(i), ss);
  }
  for (const auto& pin : m.pins) {
    const Vec3 p = project(cam, v, {pin.position[0], pin.position[1], 0});
    disc(p[0], p[1], 5, {200, 50, 50, 255}, ss);
  }
  if (o.velocity_arrows && !f.velocities.empty())
    for (int i = 0; i < n; ++i) {
      const Vec3 p = at(f.positions, i), q = point_of(f.velocities, d, i), x = point_of(f.positions, d, i);
      const Vec3 tip = project(cam, v, {x[0] + q[0] * o.arrow_seconds, x[1] + q[1] * o.arrow_seconds, 0});
      arrow(p[0], p[1], tip[0], tip[1], 2, {200, 40, 40, 255});
    }
}

// ---------------------------------------------------------------------------------------------------------------
// 1-D: a pendulum, a spring to its anchor, or beads on a line

void draw_mechanical_1d(Canvas& canvas, const Viewport& v, const MechanicalDescription& m, const MechanicalFrame& f,
                        const Camera& cam, const DrawOptions& o) {
  const int ss = canvas.supersample(), n = static_cast<int>(m.bodies.size());
  begin_pixels(canvas, v);
  const double unit = std::min(v.width, v.height);
  if (!m.forces.pendulums.empty()) {
    const auto& pend = m.forces.pendulums.front();
    const Vec3 pivot = project(cam, v, {0, 0, 0});
    thick_line(pivot[0] - 0.08 * unit, pivot[1], pivot[0] + 0.08 * unit, pivot[1], 4, kWall);
    for (int i = 0; i < n; ++i) {
      const double theta = f.positions[static_cast<size_t>(i)];
      const double L = i == pend.body ? pend.length : pend.length;
      const Vec3 bob = project(cam, v, {L * std::sin(theta), -L * std::cos(theta), 0});
      thick_line(pivot[0], pivot[1], bob[0], bob[1], 3, kStick);
      disc(pivot[0], pivot[1], 4, kInk, ss);
      ball(bob[0], bob[1], 0.06 * unit, body_color(i), ss);
      if (o.velocity_arrows && !f.velocities.empty()) {
        const double w = f.velocities[static_cast<size_t>(i)] * o.arrow_seconds;  // arc length per radian · L
        const Vec3 tip = project(cam, v, {L * std::sin(theta) + L * w * std::cos(theta), -L * std::cos(theta) + L * w * std::sin(theta), 0});
        arrow(bob[0], bob[1], tip[0], tip[1], 2, {200, 40, 40, 255});
      }
    }
    return;
  }
  // The floor the masses slide on, just below them.
  const double size = 0.14 * unit;
  const Vec3 origin = project(cam, v, {0, 0, 0});
  const double floor_y = origin[1] + size / 2 + 2;
  thick_line(v.x, floor_y + 1.5, v.x + v.width, floor_y + 1.5, 3, kWall);
  for (const auto& s : m.forces.springs) {
    const Vec3 a = project(cam, v, {f.positions[static_cast<size_t>(s.a)], 0, 0});
    Vec3 b;
    if (s.b >= 0) {
      b = project(cam, v, {f.positions[static_cast<size_t>(s.b)], 0, 0});
    } else {
      b = project(cam, v, {s.anchor[0], 0, 0});
      if (s.rest_length == 0) {
        // A zero-length spring (F = −k(x − anchor)): the anchor is where the mass rests, and the
        // mass swings through it. The spring hangs from a wall at the left edge; a tick marks the anchor.
        thick_line(b[0], floor_y - 0.35 * size, b[0], floor_y + 0.35 * size, 2, {200, 50, 50, 255});
        b[0] = v.x + 0.04 * v.width;
      }
      const double side = a[0] >= b[0] ? -1 : 1;  // the wall is behind the spring's end
      thick_line(b[0] + side * 3, origin[1] - size, b[0] + side * 3, floor_y, 6, kWall);
    }
    zig_zag(b[0], b[1], a[0], a[1], 0.025 * unit, 10, 2, kStick);
  }
  for (int i = 0; i < n; ++i) {
    const Vec3 p = project(cam, v, {f.positions[static_cast<size_t>(i)], 0, 0});
    const double r = m.bodies[static_cast<size_t>(i)].radius * cam.scale;
    if (r > 0) {
      ball(p[0], p[1], r, body_color(i), ss);
    } else {
      // A mass: a block centred on its position.
      gl_color(darker(body_color(i), 0.7));
      glRectd(p[0] - size / 2, p[1] - size / 2, p[0] + size / 2, p[1] + size / 2);
      gl_color(body_color(i));
      glRectd(p[0] - size / 2 + 2, p[1] - size / 2 + 2, p[0] + size / 2 - 2, p[1] + size / 2 - 2);
    }
    if (o.velocity_arrows && !f.velocities.empty()) {
      const double x = f.positions[static_cast<size_t>(i)] + f.velocities[static_cast<size_t>(i)] * o.arrow_seconds;
      const Vec3 tip = project(cam, v, {x, 0, 0});
      arrow(p[0], p[1] - size * 0.8, tip[0], p[1] - size * 0.8, 2, {200, 40, 40, 255});
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// 3-D

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

void lights_on() {
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glEnable(GL_NORMALIZE);
  glEnable(GL_COLOR_MATERIAL);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  const GLfloat ambient[] = {0.35f, 0.35f, 0.35f, 1}, diffuse[] = {0.75f, 0.75f, 0.72f, 1},
                specular[] = {0.35f, 0.35f, 0.35f, 1};
  const GLfloat direction[] = {0.35f, 1.0f, 0.55f, 0};  // w = 0: a directional light, in world space
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
  glLightfv(GL_LIGHT0, GL_SPECULAR, specular);
  glLightfv(GL_LIGHT0, GL_POSITION, direction);
  const GLfloat shine[] = {0.3f, 0.3f, 0.3f, 1};
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, shine);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 40);
}

void lights_off() { glDisable(GL_LIGHTING); }

// A unit sphere as triangle strips (positions double as normals).
struct SphereMesh {
  std::vector<GLfloat> vertices;
  int stacks = 12, slices = 20;
  SphereMesh() {
    for (int i = 0; i < stacks; ++i)
      for (int j = 0; j <= slices; ++j)
        for (int k = 0; k < 2; ++k) {
          const double phi = kPi * (i + k) / stacks, lambda = 2 * kPi * j / slices;
          vertices.push_back(static_cast<GLfloat>(std::sin(phi) * std::cos(lambda)));
          vertices.push_back(static_cast<GLfloat>(std::cos(phi)));
          vertices.push_back(static_cast<GLfloat>(std::sin(phi) * std::sin(lambda)));
        }
  }
  void draw(const Vec3& c, double r) const {
    glPushMatrix();
    glTranslated(c[0], c[1], c[2]);
    glScaled(r, r, r);
    const GLsizei strip = 2 * (slices + 1);
    for (int i = 0; i < stacks; ++i) glDrawArrays(GL_TRIANGLE_STRIP, i * strip, strip);
    glPopMatrix();
  }
};

const SphereMesh& sphere_mesh() {
  static const SphereMesh mesh;
  return mesh;
}

double nice_step(double range, int lines) {
  const double raw = range / lines, p = std::pow(10, std::floor(std::log10(raw))), m = raw / p;
  return p * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
}

// The height of the ground: the lowest upward-facing plane, else the bottom of a box.
std::optional<double> ground_height(const MechanicalDescription& m) {
  std::optional<double> y;
  for (const auto& p : m.colliders.planes)
    if (p.normal[1] > 0.99) y = std::min(y.value_or(kInf), p.offset / p.normal[1]);
  if (!y)
    for (const auto& b : m.colliders.boxes) y = std::min(y.value_or(kInf), b.min[1]);
  return y;
}

void ground_grid(const Vec3& centre, double half, double y, bool solid) {
  const double step = nice_step(2 * half, 12);
  const double x0 = std::floor((centre[0] - half) / step) * step, z0 = std::floor((centre[2] - half) / step) * step;
  const double x1 = centre[0] + half, z1 = centre[2] + half;
  if (solid) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1, 1);
    gl_color(kGround);
    glBegin(GL_QUADS);
    glVertex3d(x0, y, z0);
    glVertex3d(x0, y, z1);
    glVertex3d(x1, y, z1);
    glVertex3d(x1, y, z0);
    glEnd();
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  gl_color(solid ? Color{190, 188, 180, 255} : kGrid);
  glBegin(GL_LINES);
  for (double x = x0; x <= x1 + 1e-9; x += step) glVertex3d(x, y, z0), glVertex3d(x, y, z1);
  for (double z = z0; z <= z1 + 1e-9; z += step) glVertex3d(x0, y, z), glVertex3d(x1, y, z);
  glEnd();
}

void box_edges(const Vec3& a, const Vec3& b) {
  const double xs[2] = {a[0], b[0]}, ys[2] = {a[1], b[1]}, zs[2] = {a[2], b[2]};
  glBegin(GL_LINES);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      glVertex3d(xs[0], ys[i], zs[j]), glVertex3d(xs[1], ys[i], zs[j]);
      glVertex3d(xs[i], ys[0], zs[j]), glVertex3d(xs[i], ys[1], zs[j]);
      glVertex3d(xs[i], ys[j], zs[0]), glVertex3d(xs[i], ys[j], zs[1]);
    }
  glEnd();
}

// Triangles whose three sides are all sticks: a cloth's squares. A square with both
// diagonals (shear sticks) holds four such triangles, two per way of cutting it; only the
// cut along the diagonal from its lowest to its highest body index is kept, so that no
// two triangles overlap. For a triangle a < b < c that means: (a, c) is its longest stick.
std::vector<std::array<int, 3>> stick_triangles(const MechanicalDescription& m) {
  const size_t n = m.bodies.size();
  std::vector<std::vector<std::pair<int, double>>> next(n);  // (neighbour with a larger index, length), sorted
  for (const auto& s : m.sticks) {
    const int a = std::min(s.a, s.b), b = std::max(s.a, s.b);
    next[static_cast<size_t>(a)].push_back({b, s.length});
  }
  for (auto& list : next) std::sort(list.begin(), list.end());
  auto find = [&](int a, int b) -> const std::pair<int, double>* {
    const auto& list = next[static_cast<size_t>(a)];
    const auto it = std::lower_bound(list.begin(), list.end(), std::pair<int, double>{b, -kInf});
    return it != list.end() && it->first == b ? &*it : nullptr;
  };
  std::vector<std::array<int, 3>> triangles;
  for (size_t a = 0; a < n; ++a)
    for (const auto& [b, ab] : next[a])
      for (const auto& [c, bc] : next[static_cast<size_t>(b)])
        if (const auto* ac = find(static_cast<int>(a), c); ac && ac->second >= ab && ac->second >= bc)
          triangles.push_back({static_cast<int>(a), b, c});
  return triangles;
}

void draw_mechanical_3d(Canvas& canvas, const Viewport& v, const MechanicalDescription& m, const MechanicalFrame& f,
                        const Camera& cam, const DrawOptions& o) {
  const int d = 3, n = static_cast<int>(m.bodies.size());
  begin_3d(canvas, v, cam);
  lights_off();
  glLineWidth(static_cast<GLfloat>(canvas.supersample()));
  if (o.ground_grid) {
    const auto ground = ground_height(m);
    if (o.ground_centre) {
      ground_grid(*o.ground_centre, o.ground_half_width, (*o.ground_centre)[1], ground.has_value());
    } else {
      Box3 b;
      for (int i = 0; i < n; ++i) b.add(point_of(f.positions, d, i), m.bodies[static_cast<size_t>(i)].radius);
      for (const auto& box : m.colliders.boxes) b.add({box.min[0], box.min[1], box.min[2]}), b.add({box.max[0], box.max[1], box.max[2]});
      if (!b.empty()) {
        const Vec3 c = b.centre();
        const double half = std::max({b.hi[0] - b.lo[0], b.hi[2] - b.lo[2], 1e-3}) * 0.9;
        ground_grid(c, half, ground.value_or(b.lo[1]), ground.has_value());
      }
    }
  }
  gl_color(kWall);
  for (const auto& box : m.colliders.boxes) box_edges({box.min[0], box.min[1], box.min[2]}, {box.max[0], box.max[1], box.max[2]});
  if (o.trails && !f.trail.empty() && n <= 64)
    for (int i = 0; i < n; ++i) {
      gl_color(mix(body_color(i), o.background, 0.4));
      glBegin(GL_LINE_STRIP);
      for (const auto& x : f.trail) {
        const Vec3 p = point_of(x, d, i);
        glVertex3d(p[0], p[1], p[2]);
      }
      glEnd();
    }

  lights_on();
  auto triangles = m.sticks.empty() ? std::vector<std::array<int, 3>>{} : stick_triangles(m);
  if (!triangles.empty()) {
    auto triangle_normal = [](const Vec3& a, const Vec3& b, const Vec3& c) {
      const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      return Vec3{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    };
    // One winding for the whole sheet, chosen in the scene's initial (flat) layout: every
    // triangle turned to face the same side as the first one. Two-sided lighting then
    // lights the underside as the underside.
    auto initial = [&](int i) {
      const auto& p = m.bodies[static_cast<size_t>(i)].position;
      return Vec3{p[0], p[1], p[2]};
    };
    const Vec3 side = triangle_normal(initial(triangles[0][0]), initial(triangles[0][1]), initial(triangles[0][2]));
    for (auto& t : triangles) {
      const Vec3 n0 = triangle_normal(initial(t[0]), initial(t[1]), initial(t[2]));
      if (n0[0] * side[0] + n0[1] * side[1] + n0[2] * side[2] < 0) t = {t[0], t[2], t[1]};
    }
    // Smooth normals: every triangle adds its normal to its corners.
    std::vector<Vec3> normal(static_cast<size_t>(n), Vec3{0, 0, 0});
    for (const auto& t : triangles) {
      const Vec3 nn = triangle_normal(point_of(f.positions, d, t[0]), point_of(f.positions, d, t[1]),
                                      point_of(f.positions, d, t[2]));
      for (int k : t)
        for (int j = 0; j < 3; ++j) normal[static_cast<size_t>(k)][static_cast<size_t>(j)] += nn[static_cast<size_t>(j)];
    }
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1, 1);
    gl_color({214, 92, 64, 255});
    glBegin(GL_TRIANGLES);
    for (const auto& t : triangles)
      for (int k : t) {
        const Vec3& nn = normal[static_cast<size_t>(k)];
        const Vec3 p = point_of(f.positions, d, k);
        glNormal3d(nn[0], nn[1], nn[2]);
        glVertex3d(p[0], p[1], p[2]);
      }
    glEnd();
    glDisable(GL_POLYGON_OFFSET_FILL);
  } else if (!m.sticks.empty()) {
    lights_off();
    gl_color(kStick);
    glBegin(GL_LINES);
    for (const auto& s : m.sticks) {
      const Vec3 a = point_of(f.positions, d, s.a), b = point_of(f.positions, d, s.b);
      glVertex3d(a[0], a[1], a[2]), glVertex3d(b[0], b[1], b[2]);
    }
    glEnd();
    lights_on();
  }
  // Spheres with one-sided lighting: their normals are right whatever the strips' winding.
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_FALSE);
  const auto& mesh = sphere_mesh();
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, mesh.vertices.data());
  glNormalPointer(GL_FLOAT, 0, mesh.vertices.data());
  Box3 all;
  for (int i = 0; i < n; ++i) all.add(point_of(f.positions, d, i));
  const double dot_radius = std::max(all.radius(), 0.1) * 0.012;
  for (int i = 0; i < n; ++i) {
    const double r = m.bodies[static_cast<size_t>(i)].radius;
    if (r <= 0 && !triangles.empty()) continue;  // the cloth shows them
    gl_color(body_color(i));
    mesh.draw(point_of(f.positions, d, i), r > 0 ? r : dot_radius);
  }
  gl_color({200, 50, 50, 255});
  for (const auto& pin : m.pins) mesh.draw({pin.position[0], pin.position[1], pin.position[2]}, dot_radius * 1.6);
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  lights_off();
  if (o.velocity_arrows && !f.velocities.empty()) {
    gl_color({200, 40, 40, 255});
    glBegin(GL_LINES);
    for (int i = 0; i < n; ++i) {
      const Vec3 p = point_of(f.positions, d, i), q = point_of(f.velocities, d, i);
      glVertex3d(p[0], p[1], p[2]);
      glVertex3d(p[0] + q[0] * o.arrow_seconds, p[1] + q[1] * o.arrow_seconds, p[2] + q[2] * o.arrow_seconds);
    }
    glEnd();
  }
  glDisable(GL_DEPTH_TEST);
}

std::string format_number(const char* format, double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, x);
  return buffer;
}

std::vector<std::string> variable_names(const SceneDescription& scene, size_t count) {
  std::vector<std::string> names;
  if (scene.first_order)
    if (const auto* info = find_first_order_system(scene.first_order->type)) names = info->variables;
  for (size_t i = names.size(); i < count; ++i) names.push_back(std::string(1, 'y').append(std::to_string(i)));
  names.resize(count);
  return names;
}

// The overlay's text size for a viewport: 15 px on a 640 × 480 frame, down to 10 px on small ones.
double overlay_text_size(const Viewport& v) { return std::clamp(std::min(1.0 * v.width, 1.4 * v.height) / 36.0, 10.0, 15.0); }

}  // namespace

double overlay_height(const Viewport& v) { return 3.6 * overlay_text_size(v) + 8; }

// -----------------------------------------------------------------------------------------------------------------

void Recording::add(double t, std::span<const double> state, std::optional<double> energy) {
  times.push_back(t);
  states.emplace_back(state.begin(), state.end());
  if (energy) energies.push_back(*energy);
}

Color body_color(int index) {
  static const Color palette[] = {{66, 133, 214, 255}, {230, 120, 50, 255}, {70, 170, 100, 255}, {205, 70, 90, 255},
                                  {145, 100, 200, 255}, {40, 170, 180, 255}, {220, 180, 40, 255}, {150, 110, 80, 255}};
  return palette[static_cast<size_t>(index) % std::size(palette)];
}

Camera fit_camera(const SceneDescription& scene, const Recording& rec, const Viewport& v) {
  const double aspect = static_cast<double>(v.width) / v.height;
  if (scene.first_order) {
    Box3 b;
    for (const auto& y : rec.states)
      if (y.size() >= 3) b.add({y[0], y[1], y[2]});
    if (b.empty()) b.add({0, 0, 0}, 1);
    const Vec3 c = b.centre();
    const double r = std::max(b.radius(), 1e-9), fov = 35;
    const double dist = r / std::sin(fov * kPi / 360) * (aspect < 1 ? 1.1 / aspect : 1.0) * 0.95;
    const Vec3 dir{0.55, -0.75, 0.36};  // z up, seen from the front right, a little above
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    return Camera::perspective({c[0] + dir[0] / len * dist, c[1] + dir[1] / len * dist, c[2] + dir[2] / len * dist}, c,
                               {0, 0, 1}, fov);
  }
  const auto& m = *scene.mechanical;
  const int d = m.dimensions, n = static_cast<int>(m.bodies.size());
  if (d == 3) {
    Box3 b;
    for (const auto& box : m.colliders.boxes) b.add({box.min[0], box.min[1], box.min[2]}), b.add({box.max[0], box.max[1], box.max[2]});
    if (b.empty())
      for (const auto& x : rec.states)
        for (int i = 0; i < n; ++i) b.add(point_of(x, d, i), m.bodies[static_cast<size_t>(i)].radius);
    if (const auto g = ground_height(m)) b.add({b.centre()[0], *g, b.centre()[2]});
    if (b.empty()) b.add({0, 0, 0}, 1);
    const Vec3 c = b.centre();
    const double r = std::max(b.radius(), 1e-6), fov = 40;
    const double dist = r / std::sin(fov * kPi / 360) * (aspect < 1 ? 1.0 / aspect : 1.0) * 0.9;
    const Vec3 dir{0.55, 0.45, 0.85};
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    return Camera::perspective({c[0] + dir[0] / len * dist, c[1] + dir[1] / len * dist, c[2] + dir[2] / len * dist}, c,
                               {0, 1, 0}, fov);
  }
  if (d == 1 && !m.forces.pendulums.empty()) {
    const double L = m.forces.pendulums.front().length;
    return Camera::orthographic(0, -0.1 * L, std::min(v.width, v.height) / (2.6 * L));
  }
  Box2 b;
  if (d == 1) {
    for (const auto& x : rec.states)
      for (int i = 0; i < n; ++i) b.add(x[static_cast<size_t>(i)], 0, m.bodies[static_cast<size_t>(i)].radius);
    for (const auto& s : m.forces.springs)
      if (s.b < 0) b.add(s.anchor[0], 0);
    if (b.empty()) b.add(0, 0, 1);
    const double span = std::max(b.x1 - b.x0, 1e-9);
    // The middle 80% of the width (a zero-length spring's wall stands at the left edge), below the overlay.
    const double scale = v.width * 0.76 / span;
    return Camera::orthographic((b.x0 + b.x1) / 2 - 0.04 * v.width / scale, overlay_height(v) / 2 / scale, scale);
  }
  for (const auto& box : m.colliders.boxes) b.add(box.min[0], box.min[1]), b.add(box.max[0], box.max[1]);
  for (const auto& s : m.colliders.segments) b.add(s.a[0], s.a[1]), b.add(s.b[0], s.b[1]);
  if (m.colliders.boxes.empty())
    for (const auto& x : rec.states)
      for (int i = 0; i < n; ++i) b.add(x[static_cast<size_t>(2 * i)], x[static_cast<size_t>(2 * i + 1)], m.bodies[static_cast<size_t>(i)].radius);
  for (const auto& g : m.forces.central_gravity) b.add(g.centre[0], g.centre[1]);
  for (const auto& s : m.forces.springs)
    if (s.b < 0) b.add(s.anchor[0], s.anchor[1]);
  if (b.empty()) b.add(0, 0, 1);
  // A ground plane just in view below everything.
  if (!m.colliders.planes.empty() && m.colliders.boxes.empty())
    for (const auto& p : m.colliders.planes)
      if (std::abs(p.normal[1]) > 0.99) b.add((b.x0 + b.x1) / 2, p.offset / p.normal[1] - 0.05 * (b.y1 - b.y0));
  double w = b.x1 - b.x0, h = b.y1 - b.y0;
  if (w <= 0 && h <= 0) w = h = 1;
  // Below the overlay's band, with a margin of 5% on each side.
  const double band = overlay_height(v), usable = std::max(v.height - band, 0.5 * v.height);
  const double scale = std::min(w > 0 ? v.width * 0.9 / w : kInf, h > 0 ? usable * 0.9 / h : kInf);
  return Camera::orthographic((b.x0 + b.x1) / 2, (b.y0 + b.y1) / 2 + (v.height - usable) / 2 / scale, scale);
}

void fit_ground(const SceneDescription& scene, const Recording& rec, DrawOptions& options) {
  if (!scene.mechanical || scene.mechanical->dimensions != 3) return;
  const auto& m = *scene.mechanical;
  const int n = static_cast<int>(m.bodies.size());
  Box3 b;
  for (const auto& box : m.colliders.boxes) b.add({box.min[0], box.min[1], box.min[2]}), b.add({box.max[0], box.max[1], box.max[2]});
  for (const auto& x : rec.states)
    for (int i = 0; i < n; ++i) b.add(point_of(x, 3, i), m.bodies[static_cast<size_t>(i)].radius);
  if (b.empty()) return;
  const Vec3 c = b.centre();
  options.ground_centre = Vec3{c[0], ground_height(m).value_or(b.lo[1]), c[2]};
  options.ground_half_width = std::max({b.hi[0] - b.lo[0], b.hi[2] - b.lo[2], 1e-3}) * 0.9;
}

void draw_mechanical(Canvas& canvas, const Viewport& v, const SceneDescription& scene, const MechanicalFrame& frame,
                     const Camera& camera, const DrawOptions& options) {
  const auto& m = *scene.mechanical;
  if (m.dimensions == 1)
    draw_mechanical_1d(canvas, v, m, frame, camera, options);
  else if (m.dimensions == 2)
    draw_mechanical_2d(canvas, v, m, frame, camera, options);
  else
    draw_mechanical_3d(canvas, v, m, frame, camera, options);
}

void draw_trajectory_3d(Canvas& canvas, const Viewport& v, const Recording& rec, size_t upto, const Camera& cam,
                        const std::vector<std::string>& names, const DrawOptions&) {
  if (rec.size() == 0) return;
  upto = std::min(upto, rec.size() - 1);
  begin_3d(canvas, v, cam);
  // Axes from the corner of the bounding box, labelled.
  Box3 b;
  for (const auto& y : rec.states) b.add({y[0], y[1], y[2]});
  const double arm = 0.25 * std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
  glLineWidth(static_cast<GLfloat>(canvas.supersample()));
  gl_color({150, 150, 150, 255});
  glBegin(GL_LINES);
  for (int k = 0; k < 3; ++k) {
    Vec3 tip = b.lo;
    tip[static_cast<size_t>(k)] += arm;
    glVertex3d(b.lo[0], b.lo[1], b.lo[2]);
    glVertex3d(tip[0], tip[1], tip[2]);
    const Vec3 at = project(cam, v, {tip[0], tip[1], tip[2]});
    if (static_cast<size_t>(k) < names.size())
      canvas.text(static_cast<int>(at[0]) + 3, static_cast<int>(at[1]) + 4, names[static_cast<size_t>(k)],
                  {12, {120, 120, 120, 255}});
  }
  glEnd();
  glLineWidth(1.5f * static_cast<GLfloat>(canvas.supersample()));
  const double t0 = rec.times.front(), t1 = rec.times.back() > t0 ? rec.times.back() : t0 + 1;
  glBegin(GL_LINE_STRIP);
  for (size_t i = 0; i <= upto; ++i) {
    const auto& y = rec.states[i];
    gl_color(time_color((rec.times[i] - t0) / (t1 - t0)));
    glVertex3d(y[0], y[1], y[2]);
  }
  glEnd();
  glDisable(GL_DEPTH_TEST);
  const auto& y = rec.states[upto];
  const Vec3 head = project(cam, v, {y[0], y[1], y[2]});
  begin_pixels(canvas, v);
  disc(head[0], head[1], 5, {20, 20, 20, 255}, canvas.supersample());
  disc(head[0], head[1], 3.5, time_color((rec.times[upto] - t0) / (t1 - t0)), canvas.supersample());
}

void draw_time_series(Canvas& canvas, const Viewport& v, const Recording& rec, size_t upto,
                      const std::vector<std::string>& names, const DrawOptions&) {
  if (rec.size() == 0) return;
  upto = std::min(upto, rec.size() - 1);
  const size_t count = rec.states.front().size();
  begin_pixels(canvas, v);
  const double left = v.x + 48, right = v.x + v.width - 205, top = v.y + overlay_height(v) + 30, bottom = v.y + v.height - 34;
  const double t0 = rec.times.front(), t1 = rec.times.back() > t0 ? rec.times.back() : t0 + 1;
  auto px = [&](double t) { return left + (t - t0) / (t1 - t0) * (right - left); };
  auto py = [&](double y) { return bottom - y * (bottom - top); };
  // Axes, grid and tick labels.
  const TextStyle tick{11, {110, 110, 110, 255}, Align::center};
  const double step = nice_step(t1 - t0, 6);
  for (double t = std::ceil(t0 / step) * step; t <= t1 + 1e-9 * step; t += step) {
    thick_line(px(t), top, px(t), bottom, 1, kGrid);
    canvas.text(static_cast<int>(px(t)), static_cast<int>(bottom) + 15, format_number("%g", t), tick);
  }
  for (int i = 0; i <= 4; ++i) {
    thick_line(left, py(i / 4.0), right, py(i / 4.0), 1, kGrid);
    canvas.text(static_cast<int>(left) - 6, static_cast<int>(py(i / 4.0)) + 4, format_number("%g", i / 4.0),
                {11, {110, 110, 110, 255}, Align::right});
  }
  thick_line(left, bottom, right, bottom, 1.5, kInk);
  thick_line(left, top, left, bottom, 1.5, kInk);
  canvas.text(static_cast<int>(left), static_cast<int>(top) - 8, "each variable / its largest magnitude over the run",
              {11, {110, 110, 110, 255}});
  // The lines, up to now.
  for (size_t k = 0; k < count; ++k) {
    double peak = 0;
    for (const auto& y : rec.states) peak = std::max(peak, std::abs(y[k]));
    if (!(peak > 0)) peak = 1;
    const Color c = body_color(static_cast<int>(k));
    for (size_t i = 1; i <= upto; ++i)
      thick_line(px(rec.times[i - 1]), py(rec.states[i - 1][k] / peak), px(rec.times[i]), py(rec.states[i][k] / peak), 2.2, c);
    const double ex = px(rec.times[upto]), ey = py(rec.states[upto][k] / peak);
    disc(ex, ey, 3.5, c, canvas.supersample());
    const std::string name = k < names.size() ? names[k] : std::string(1, 'y').append(std::to_string(k));
    canvas.text(static_cast<int>(ex) + 7, static_cast<int>(ey) + 4, name, {12, darker(c, 0.8)});
    // Legend: the name and the scale it was divided by.
    const int ly = static_cast<int>(top) + 14 + static_cast<int>(k) * 18;
    disc(right + 52, ly - 4, 4, c, canvas.supersample());
    canvas.text(static_cast<int>(right) + 60, ly, name + "  max " + format_number("%.3g", peak), {12, kInk});
  }
  thick_line(px(rec.times[upto]), top, px(rec.times[upto]), bottom, 1, {150, 150, 150, 255});
}

void draw_overlay(Canvas& canvas, const Viewport& v, const Overlay& o) {
  // Two lines (three with a note on frames wide enough): "title   t = ...", then the energy drift.
  const double size = overlay_text_size(v), line = 1.3 * size;
  const int x = v.x + static_cast<int>(0.6 * size);
  double y = v.y + 1.3 * size;
  const TextStyle title{size, kInk}, small{0.87 * size, kInk};
  canvas.text(x, static_cast<int>(y), o.title, title);
  canvas.text(x + text_width(o.title, title) + static_cast<int>(size), static_cast<int>(y),
              "t = " + format_number("%.2f", o.time), small);
  if (o.energy_drift) {
    y += line;
    canvas.text(x, static_cast<int>(y), "\u0394E/|E\u2080| = " + format_number("%+.2e", *o.energy_drift), small);
  }
  if (!o.note.empty() && v.width >= 400) {
    y += line;
    canvas.text(x, static_cast<int>(y), o.note, {0.8 * size, {110, 110, 110, 255}});
  }
}

void draw_frame(Canvas& canvas, const Viewport& v, const SceneDescription& scene, const Recording& rec, size_t index,
                const Camera& camera, const DrawOptions& options, const std::string& note) {
  canvas.clear(v, options.background);
  if (rec.size() == 0) return;
  index = std::min(index, rec.size() - 1);
  Overlay overlay{scene.name, rec.times[index], std::nullopt, note};
  if (scene.mechanical) {
    const auto& state = rec.states[index];
    const size_t half = state.size() / 2;
    MechanicalFrame frame{std::span<const double>(state).first(half), std::span<const double>(state).subspan(half), {}};
    if (options.trails) {
      const size_t first = index > static_cast<size_t>(options.trail_frames) ? index - static_cast<size_t>(options.trail_frames) : 0;
      for (size_t i = first; i <= index; ++i) frame.trail.push_back(std::span<const double>(rec.states[i]).first(half));
    }
    draw_mechanical(canvas, v, scene, frame, camera, options);
    if (index < rec.energies.size() && rec.energies.front() != 0)
      overlay.energy_drift = (rec.energies[index] - rec.energies.front()) / std::abs(rec.energies.front());
  } else {
    const size_t count = rec.states[index].size();
    const auto names = variable_names(scene, count);
    if (count == 3)
      draw_trajectory_3d(canvas, v, rec, index, camera, names, options);
    else
      draw_time_series(canvas, v, rec, index, names, options);
  }
  if (options.overlay) draw_overlay(canvas, v, overlay);
}

}  // namespace motus::render
