// 2-D mechanical scenes, orthographic, in pixels: walls (planes, boxes, segments), central
// bodies, trails, springs, sticks, balls, pins and velocity arrows. Each dimension draws its
// scenes its own way, so each has its own file.
#include <GL/gl.h>

#include "motus/render/draw_primitives.hpp"

namespace motus::render::detail {

namespace {

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

}  // namespace

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
  if (o.trails && !f.trail.empty() && static_cast<size_t>(n) <= kMostTrailedBodies) {
    const size_t count = f.trail.size();
    for (int i = 0; i < n; ++i)
      for (size_t k = 1; k < count; ++k) {
        const Vec3 a = at(f.trail[k - 1], i), b = at(f.trail[k], i);
        thick_line(a[0], a[1], b[0], b[1], 2, body_color(i + o.first_body_colour), 0.15 + 0.6 * static_cast<double>(k) / count);
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
      ball(p[0], p[1], r, body_color(i + o.first_body_colour), ss);
    else
      disc(p[0], p[1], sticks ? 3.5 : 6, sticks ? kInk : body_color(i + o.first_body_colour), ss);
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

}  // namespace motus::render::detail
