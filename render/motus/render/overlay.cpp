// The text overlay in a viewport's top-left corner (title, time, energy drift, a note) and the
// height of its band. Separate: it is drawn over every kind of scene.
#include "motus/render/draw_primitives.hpp"

namespace motus::render {

using namespace detail;

double overlay_height(const Viewport& v) { return 3.6 * overlay_text_size(v) + 8; }

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

}  // namespace motus::render
