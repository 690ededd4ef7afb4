// A first-order scene with other than three variables (World2): each variable against time as a
// chart, normalised by its largest magnitude, with a legend that says what each variable is.
// Separate: a chart, not a scene in space.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "motus/render/draw_primitives.hpp"

namespace motus::render {

using namespace detail;

namespace {

// The labels at the lines' ends, moved apart (keeping their order) so that none overlaps the
// next: a chart whose lines meet at the end (World2's P, CI and CIAF in 2100) stays readable.
std::vector<double> spread_labels(std::vector<double> y, double gap, double top, double bottom) {
  std::vector<size_t> order(y.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return y[a] < y[b]; });
  for (size_t i = 1; i < order.size(); ++i) y[order[i]] = std::max(y[order[i]], y[order[i - 1]] + gap);
  // If that pushed the lowest below the axis, push back up from the bottom.
  if (!order.empty() && y[order.back()] > bottom) {
    y[order.back()] = bottom;
    for (size_t i = order.size() - 1; i-- > 0;) y[order[i]] = std::min(y[order[i]], y[order[i + 1]] - gap);
  }
  for (auto& value : y) value = std::max(value, top);
  return y;
}

// The time axis's tick step: the finest round step (1, 2 or 5 × 10^k; about one tick per 45 pixels,
// at most 8) whose labels, each centred on its tick, stay two spaces apart. A step from the pixels
// alone ran labels into each other when they are long: World2 over one year ticked every 0.1 year,
// 34 px apart, under labels "1900.1" 36 px wide ("19001900.11900.2…1901").
double time_step(double t0, double t1, double pixels, const TextStyle& style) {
  double step = nice_step(t1 - t0, std::clamp(static_cast<int>(pixels / 45), 2, 8));
  const double gap = 2.0 * text_width(" ", style);
  for (int coarser = 0; coarser < 64; ++coarser) {
    const double first = std::ceil(t0 / step) * step;
    int widest = 0;
    for (int i = 0; first + i * step <= t1 + 1e-9 * step; ++i)
      widest = std::max(widest, text_width(format_number("%g", first + i * step), style));
    if (step / (t1 - t0) * pixels >= widest + gap) break;
    // The next round step: 1 → 2 → 5 → 10 (the mantissa read back rounded: 0.2 is not 2·10⁻¹ exactly).
    const double power = std::pow(10, std::floor(std::log10(step) + 1e-9)), mantissa = std::round(step / power);
    step = power * (mantissa < 2 ? 2 : mantissa < 5 ? 5 : 10);
  }
  return step;
}

}  // namespace

void draw_time_series(Canvas& canvas, const Viewport& v, const Recording& rec, size_t upto, const SeriesLabels& labels,
                      const DrawOptions&) {
  if (rec.size() == 0) return;
  upto = std::min(upto, rec.size() - 1);
  const size_t count = rec.states.front().size();
  const bool explained = labels.meanings.size() == count;
  begin_pixels(canvas, v);
  const double legend_width = explained ? std::min(210.0, 0.38 * v.width) : 160.0;
  const double left = v.x + 48, right = v.x + v.width - legend_width - 45, top = v.y + overlay_height(v) + 30,
               bottom = v.y + v.height - 40;
  const double t0 = rec.times.front(), t1 = rec.times.back() > t0 ? rec.times.back() : t0 + 1;
  auto px = [&](double t) { return left + (t - t0) / (t1 - t0) * (right - left); };
  // Each variable over its largest magnitude over the run: from 0 to 1, or from −1 when one goes
  // below 0 (Van der Pol's x and v swing both ways).
  std::vector<double> peaks(count, 1), ends(count);
  bool negative = false;
  for (size_t k = 0; k < count; ++k) {
    double peak = 0;
    for (const auto& y : rec.states) peak = std::max(peak, std::abs(y[k])), negative = negative || y[k] < 0;
    if (peak > 0) peaks[k] = peak;
  }
  const double low = negative ? -1 : 0;
  auto py = [&](double y) { return bottom - (y - low) / (1 - low) * (bottom - top); };
  const Color grey{90, 94, 104, 255};
  // Axes, grid and tick labels; the time axis says what it counts.
  const TextStyle tick{11, grey, Align::center};
  const double step = time_step(t0, t1, right - left, tick);
  // (Each tick as first + i·step: a sum of steps drifts, 1900 + 0.2 five times is 1901.0000000000002.)
  const double first = std::ceil(t0 / step) * step;
  for (int i = 0; first + i * step <= t1 + 1e-9 * step; ++i) {
    const double t = first + i * step;
    thick_line(px(t), top, px(t), bottom, 1, kGrid);
    canvas.text(static_cast<int>(px(t)), static_cast<int>(bottom) + 15, format_number("%g", t), tick);
  }
  canvas.text(static_cast<int>((left + right) / 2), static_cast<int>(bottom) + 30,
              labels.time_unit == "year" ? "year" : "t [" + labels.time_unit + "]", {11, kInk, Align::center});
  for (int i = 0; i <= 4; ++i) {
    const double y = low + (1 - low) * i / 4.0;
    thick_line(left, py(y), right, py(y), y == 0 && negative ? 1.5 : 1, y == 0 && negative ? grey : kGrid);
    canvas.text(static_cast<int>(left) - 6, static_cast<int>(py(y)) + 4, format_number("%g", y), {11, grey, Align::right});
  }
  thick_line(left, bottom, right, bottom, 1.5, kInk);
  thick_line(left, top, left, bottom, 1.5, kInk);
  canvas.text(static_cast<int>(left), static_cast<int>(top) - 8, "each variable / its largest magnitude over the run",
              {11, grey});
  // The lines, up to now; the end labels spread apart afterwards.
  for (size_t k = 0; k < count; ++k) {
    const Color c = body_color(static_cast<int>(k));
    for (size_t i = 1; i <= upto; ++i)
      thick_line(px(rec.times[i - 1]), py(rec.states[i - 1][k] / peaks[k]), px(rec.times[i]),
                 py(rec.states[i][k] / peaks[k]), 2.2, c);
    ends[k] = py(rec.states[upto][k] / peaks[k]);
    disc(px(rec.times[upto]), ends[k], 3.5, c, canvas.supersample());
  }
  const auto label_y = spread_labels(ends, 13, top, bottom);
  const std::string fallback = "y";
  for (size_t k = 0; k < count; ++k) {
    const Color c = body_color(static_cast<int>(k));
    const std::string& name = k < labels.names.size() ? labels.names[k] : fallback;
    canvas.text(static_cast<int>(px(rec.times[upto])) + 7, static_cast<int>(label_y[k]) + 4, name, {12, darker(c, 0.8)});
    // Legend: the name, what it is, and the largest value it was divided by.
    const double row = explained ? 31 : 18;
    const int ly = static_cast<int>(top + 14 + static_cast<double>(k) * row);
    const double lx = right + 40;
    disc(lx, ly - 4, 4, c, canvas.supersample());
    if (explained) {
      // "population (people)": the meaning on the first line, the unit after the largest value.
      const std::string& meaning = labels.meanings[k];
      const size_t open = meaning.rfind(" (");
      const bool has_unit = open != std::string::npos && meaning.back() == ')';
      const std::string what = has_unit ? meaning.substr(0, open) : meaning;
      std::string unit = has_unit ? meaning.substr(open + 2, meaning.size() - open - 3) : "";
      if (unit == "fraction") unit.clear();
      canvas.text(static_cast<int>(lx) + 9, ly, name + "  " + what, {12, kInk});
      canvas.text(static_cast<int>(lx) + 9, ly + 13,
                  "largest " + format_number("%.3g", peaks[k]) + (unit.empty() ? "" : " " + unit), {11, grey});
    } else {
      canvas.text(static_cast<int>(lx) + 9, ly, name + "  largest " + format_number("%.3g", peaks[k]), {12, kInk});
    }
  }
  thick_line(px(rec.times[upto]), top, px(rec.times[upto]), bottom, 1, {150, 150, 150, 255});
}

}  // namespace motus::render
