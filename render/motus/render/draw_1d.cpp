// 1-D mechanical scenes: a pendulum (rod and bob at angle x), a spring to its anchor (a mass on
// a zig-zag), or beads on a line. Separate from 2-D: one coordinate per body is no point on the
// screen, so each kind of 1-D scene is laid out its own way.
#include <GL/gl.h>

#include <algorithm>

#include "motus/render/draw_primitives.hpp"

namespace motus::render::detail {

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
      ball(bob[0], bob[1], 0.06 * unit, body_color(i + o.first_body_colour), ss);
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
      ball(p[0], p[1], r, body_color(i + o.first_body_colour), ss);
    } else {
      // A mass: a block centred on its position.
      gl_color(darker(body_color(i + o.first_body_colour), 0.7));
      glRectd(p[0] - size / 2, p[1] - size / 2, p[0] + size / 2, p[1] + size / 2);
      gl_color(body_color(i + o.first_body_colour));
      glRectd(p[0] - size / 2 + 2, p[1] - size / 2 + 2, p[0] + size / 2 - 2, p[1] + size / 2 - 2);
    }
    if (o.velocity_arrows && !f.velocities.empty()) {
      const double x = f.positions[static_cast<size_t>(i)] + f.velocities[static_cast<size_t>(i)] * o.arrow_seconds;
      const Vec3 tip = project(cam, v, {x, 0, 0});
      arrow(p[0], p[1] - size * 0.8, tip[0], p[1] - size * 0.8, 2, {200, 40, 40, 255});
    }
  }
}

}  // namespace motus::render::detail
