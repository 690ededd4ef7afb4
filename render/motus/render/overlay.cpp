// The text overlay in a viewport's top-left corner (title, time, energy drift, a note) and the
// height of its band. Separate: it is drawn over every kind of scene.
#include <GL/gl.h>

#include <algorithm>
#include <cmath>

#include "motus/render/draw_primitives.hpp"

namespace motus::render {

using namespace detail;

double overlay_height(const Viewport& v) { return 3.6 * overlay_text_size(v) + 8; }

void draw_overlay(Canvas& canvas, const Viewport& v, const Overlay& o) {
  // Two lines (three with a note that fits): "title   t = ...", then the energy drift.
  const double size = overlay_text_size(v), line = 1.3 * size;
  const int x = v.x + static_cast<int>(0.6 * size);
  double y = v.y + 1.3 * size;
  const TextStyle title{size, kInk}, small{0.87 * size, kInk};
  // A light box behind the text, so that it stays legible over a body, a wall or a trail — and in
  // a GIF, whose 256 colours would otherwise blur a grey line into its background.
  // The note (integrator, --set overrides) whenever it fits across the frame: a rule of 400 px wide
  // frames left a 320 px GIF's "velocity-verlet dt=0.02" out, and the picture said nothing of it.
  const TextStyle note_style{0.8 * size, {70, 74, 84, 255}};
  const bool note_shown = !o.note.empty() && (x - v.x) + text_width(o.note, note_style) + 0.6 * size <= v.width;
  const int lines = 1 + (o.energy_drift ? 1 : 0) + (note_shown ? 1 : 0);
  // Two decimals of a second (none of a year), or as many as tell two frames apart.
  int decimals = o.time_unit == "year" ? 0 : 2;
  if (o.time_step > 0 && std::isfinite(o.time_step))
    decimals = std::clamp(static_cast<int>(std::ceil(-std::log10(o.time_step) - 1e-9)), decimals, 6);
  const std::string format = "%." + std::to_string(decimals) + "f";
  const std::string time = o.time_unit == "year" ? "year " + format_number(format.c_str(), o.time)
                                                 : "t = " + format_number(format.c_str(), o.time) + " " + o.time_unit;
  const std::string first = o.title + "    " + time;
  int box = text_width(first, title);
  const std::string drift_label = o.energy_in_joules ? "\u0394E = " : "\u0394E/|E\u2080| = ";
  const std::string drift_unit = o.energy_in_joules ? " J" : "";
  if (o.energy_drift) box = std::max(box, text_width(drift_label + "+0.00e+00" + drift_unit, small));
  if (note_shown) box = std::max(box, text_width(o.note, note_style));
  begin_pixels(canvas, v);
  gl_color({255, 255, 255, 255}, 0.78);
  glRectd(v.x + 0.25 * size, v.y + 0.2 * size, x + box + 0.5 * size, v.y + 0.4 * size + lines * line);
  canvas.text(x, static_cast<int>(y), o.title, title);
  canvas.text(x + text_width(o.title, title) + static_cast<int>(size), static_cast<int>(y),
              time, small);
  if (o.energy_drift) {
    y += line;
    canvas.text(x, static_cast<int>(y), drift_label + format_number("%+.2e", *o.energy_drift) + drift_unit, small);
  }
  if (note_shown) {
    y += line;
    canvas.text(x, static_cast<int>(y), o.note, note_style);
  }
}

void draw_scale_bar(Canvas& canvas, const Viewport& v, const Camera& camera) {
  if (camera.is_perspective() || !(camera.scale > 0) || !std::isfinite(camera.scale)) return;
  // A round length (1, 2 or 5 × 10^k m) about a fifth of the frame wide, at the bottom left.
  const double target = 0.2 * v.width / camera.scale;
  const double power = std::pow(10, std::floor(std::log10(target))), m = target / power;
  const double metres = power * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
  const double pixels = metres * camera.scale;
  const double size = overlay_text_size(v);
  const double x0 = v.x + 0.8 * size, y0 = v.y + v.height - 0.9 * size;
  begin_pixels(canvas, v);
  gl_color({255, 255, 255, 255}, 0.78);
  glRectd(x0 - 0.3 * size, y0 - 1.5 * size, x0 + pixels + 0.3 * size, y0 + 0.5 * size);
  thick_line(x0, y0, x0 + pixels, y0, 2, kInk);
  thick_line(x0, y0 - 0.35 * size, x0, y0 + 0.35 * size, 1.5, kInk);
  thick_line(x0 + pixels, y0 - 0.35 * size, x0 + pixels, y0 + 0.35 * size, 1.5, kInk);
  canvas.text(static_cast<int>(x0 + pixels / 2), static_cast<int>(y0 - 0.5 * size),
              format_number("%g", metres) + " m", {0.8 * size, kInk, Align::center});
}

}  // namespace motus::render
