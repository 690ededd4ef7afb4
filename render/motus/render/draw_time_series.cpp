// A first-order scene with other than three variables (World2): each variable against time as a
// chart, normalised by its largest magnitude, with a legend. Separate: a chart, not a scene in space.
#include <algorithm>
#include <cmath>

#include "motus/render/draw_primitives.hpp"

namespace motus::render {

using namespace detail;

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

}  // namespace motus::render
