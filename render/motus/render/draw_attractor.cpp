// A first-order scene with three variables (an attractor): its 3-D trajectory coloured by time,
// with labelled axes and a dot at the current state. Separate from the mechanical 3-D scenes: no bodies.
#include <GL/gl.h>

#include <algorithm>

#include "motus/render/draw_primitives.hpp"

namespace motus::render {

using namespace detail;

void draw_trajectory_3d(Canvas& canvas, const Viewport& v, const Recording& rec, size_t upto, const Camera& cam,
                        const SeriesLabels& labels, const DrawOptions&) {
  const auto& names = labels.names;
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
  // The key to the colours: time, from the start to the end of the run, at the bottom right.
  const double size = overlay_text_size(v), bar = std::min(0.3 * v.width, 160.0), h = 0.55 * size;
  const double x1 = v.x + v.width - 1.2 * size, x0 = x1 - bar, y0 = v.y + v.height - 2.2 * size;
  for (int i = 0; i < 64; ++i) {
    gl_color(time_color((i + 0.5) / 64.0));
    glRectd(x0 + bar * i / 64.0, y0, x0 + bar * (i + 1) / 64.0 + 0.5, y0 + h);
  }
  const Color grey{90, 94, 104, 255};
  const std::string unit = labels.time_unit == "year" ? "" : " " + labels.time_unit;
  canvas.text(static_cast<int>(x0), static_cast<int>(y0 + h + 1.1 * size), "t = " + format_number("%g", t0) + unit,
              {0.8 * size, grey, Align::left});
  canvas.text(static_cast<int>(x1), static_cast<int>(y0 + h + 1.1 * size), format_number("%g", t1) + unit,
              {0.8 * size, grey, Align::right});
  canvas.text(static_cast<int>((x0 + x1) / 2), static_cast<int>(y0 - 0.35 * size), "colour: time", {0.8 * size, grey, Align::center});
}

}  // namespace motus::render
