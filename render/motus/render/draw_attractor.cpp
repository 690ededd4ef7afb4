// A first-order scene with three variables (an attractor): its 3-D trajectory coloured by time,
// with labelled axes and a dot at the current state. Separate from the mechanical 3-D scenes: no bodies.
#include <GL/gl.h>

#include <algorithm>

#include "motus/render/draw_primitives.hpp"

namespace motus::render {

using namespace detail;

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

}  // namespace motus::render
