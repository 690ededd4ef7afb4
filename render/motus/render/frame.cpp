// One frame of a run: the recording, the body palette, the camera and ground fitted to a whole
// run, and draw_mechanical / draw_frame choosing which drawer draws the scene. Separate: apart
// from the background it draws nothing itself, it decides what is drawn.
#include <algorithm>
#include <cmath>

#include "motus/render/draw_primitives.hpp"
#include "motus/systems/system_catalog.hpp"

namespace motus::render {

using namespace detail;

namespace {

std::vector<std::string> variable_names(const SceneDescription& scene, size_t count) {
  std::vector<std::string> names;
  if (scene.first_order) {
    names = scene.first_order->variables;  // the loader's: the catalog's names, or an "equations" system's own
    if (names.empty())
      if (const auto* info = find_first_order_system(scene.first_order->type)) names = info->variables;
  }
  for (size_t i = names.size(); i < count; ++i) names.push_back(std::string(1, 'y').append(std::to_string(i)));
  names.resize(count);
  return names;
}

SeriesLabels series_labels(const SceneDescription& scene, size_t count) {
  SeriesLabels labels{variable_names(scene, count), {}, "s"};
  if (scene.first_order)
    if (const auto* info = find_first_order_system(scene.first_order->type)) {
      if (info->meanings.size() == count) labels.meanings = info->meanings;
      labels.time_unit = info->time_unit;
    }
  return labels;
}

}  // namespace

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

Camera fit_camera(const SceneDescription& scene, const Recording& recording, const Viewport& v) {
  const Recording* one[] = {&recording};
  return fit_camera(scene, one, v);
}

Camera fit_camera(const SceneDescription& scene, std::span<const Recording* const> runs, const Viewport& v) {
  const double aspect = static_cast<double>(v.width) / v.height;
  if (scene.first_order) {
    Box3 b;
    for (const Recording* rec : runs)
      for (const auto& y : rec->states)
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
      for (const Recording* rec : runs)
        for (const auto& x : rec->states)
          for (int i = 0; i < n; ++i) b.add(point_of(x, d, i), m.bodies[static_cast<size_t>(i)].radius);
    if (const auto g = ground_height(m)) b.add({b.centre()[0], *g, b.centre()[2]});
    if (b.empty()) b.add({0, 0, 0}, 1);
    const Vec3 c = b.centre();
    const double r = std::max(b.radius(), 1e-6), fov = 40;
    double dist = r / std::sin(fov * kPi / 360) * (aspect < 1 ? 1.0 / aspect : 1.0) * 0.9;
    const Vec3 dir{0.55, 0.45, 0.85};
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    auto camera_at = [&](double distance) {
      return Camera::perspective(
          {c[0] + dir[0] / len * distance, c[1] + dir[1] / len * distance, c[2] + dir[2] / len * distance}, c, {0, 1, 0},
          fov);
    };
    // Close in (0.9 of the bounding sphere's distance: the scene fills the frame), but back off
    // until every corner of the box is in the frame: the nearest corner of a box, nearer the
    // eye, is drawn larger than the sphere's fit allows (bouncing_balls_3d's fell 23 px off).
    auto all_in = [&](const Camera& camera) {
      for (int k = 0; k < 8; ++k) {
        const Vec3 corner{k & 1 ? b.hi[0] : b.lo[0], k & 2 ? b.hi[1] : b.lo[1], k & 4 ? b.hi[2] : b.lo[2]};
        const Vec3 p = project(camera, v, corner);
        if (!(p[2] > 0 && p[0] >= v.x && p[0] <= v.x + v.width && p[1] >= v.y && p[1] <= v.y + v.height)) return false;
      }
      return true;
    };
    for (int tries = 0; tries < 30 && !all_in(camera_at(dist)); ++tries) dist *= 1.05;
    return camera_at(dist);
  }
  if (d == 1 && !m.forces.pendulums.empty()) {
    const double L = m.forces.pendulums.front().length;
    return Camera::orthographic(0, -0.1 * L, std::min(v.width, v.height) / (2.6 * L));
  }
  Box2 b;
  if (d == 1) {
    for (const Recording* rec : runs)
      for (const auto& x : rec->states)
        for (int i = 0; i < n; ++i) b.add(x[static_cast<size_t>(i)], 0, m.bodies[static_cast<size_t>(i)].radius);
    for (const auto& s : m.forces.springs)
      if (s.b < 0) b.add(s.anchor[0], 0);
    if (b.empty()) b.add(0, 0, 1);
    const double span = std::max(b.x1 - b.x0, 1e-9);
    // 76% of the width, moved right by 4% of it (a zero-length spring's wall stands at the left edge), below the overlay.
    const double scale = v.width * 0.76 / span;
    return Camera::orthographic((b.x0 + b.x1) / 2 - 0.04 * v.width / scale, overlay_height(v) / 2 / scale, scale);
  }
  for (const auto& box : m.colliders.boxes) b.add(box.min[0], box.min[1]), b.add(box.max[0], box.max[1]);
  for (const auto& s : m.colliders.segments) b.add(s.a[0], s.a[1]), b.add(s.b[0], s.b[1]);
  if (m.colliders.boxes.empty())
    for (const Recording* rec : runs)
      for (const auto& x : rec->states)
        for (int i = 0; i < n; ++i)
          b.add(x[static_cast<size_t>(2 * i)], x[static_cast<size_t>(2 * i + 1)], m.bodies[static_cast<size_t>(i)].radius);
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
  // Below the overlay's band and above the scale bar's (draw_scale_bar: its box reaches 2.4 text
  // sizes up from the bottom; a body there was drawn under it), with a margin of 5% on each side.
  const double band = overlay_height(v), bar = 2.4 * overlay_text_size(v);
  const double usable = std::max(v.height - band - bar, 0.5 * v.height);
  const double scale = std::min(w > 0 ? v.width * 0.9 / w : kInf, h > 0 ? usable * 0.9 / h : kInf);
  // (The usable band's middle is (band − bar)/2 pixels below the frame's.)
  return Camera::orthographic((b.x0 + b.x1) / 2, (b.y0 + b.y1) / 2 + (band - bar) / 2 / scale, scale);
}

std::vector<bool> in_a_shared_view(const SceneDescription& scene, const std::vector<Recording>& runs, size_t reference,
                                   std::vector<bool> ran) {
  if (reference >= runs.size()) return ran;
  const auto states = [&](size_t e, const auto& visit) {
    for (const auto& x : runs[e].states) visit(x);
  };
  return in_a_shared_view(scene, states, reference, std::move(ran));
}

void fit_ground(const SceneDescription& scene, const Recording& recording, DrawOptions& options) {
  const Recording* one[] = {&recording};
  fit_ground(scene, one, options);
}

void fit_ground(const SceneDescription& scene, std::span<const Recording* const> runs, DrawOptions& options) {
  if (!scene.mechanical || scene.mechanical->dimensions != 3) return;
  const auto& m = *scene.mechanical;
  const int n = static_cast<int>(m.bodies.size());
  Box3 b;
  for (const auto& box : m.colliders.boxes) b.add({box.min[0], box.min[1], box.min[2]}), b.add({box.max[0], box.max[1], box.max[2]});
  for (const Recording* rec : runs)
    for (const auto& x : rec->states)
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

void draw_frame(Canvas& canvas, const Viewport& v, const SceneDescription& scene, const Recording& rec, size_t index,
                const Camera& camera, const DrawOptions& options, const std::string& note) {
  canvas.clear(v, options.background);
  if (rec.size() == 0) return;
  index = std::min(index, rec.size() - 1);
  Overlay overlay{scene.name, rec.times[index], std::nullopt, note};
  overlay.time_step = options.frame_interval;
  if (scene.mechanical) {
    const auto& state = rec.states[index];
    const size_t half = state.size() / 2;
    MechanicalFrame frame{std::span<const double>(state).first(half), std::span<const double>(state).subspan(half), {}};
    if (options.trails) {
      // The states of the last trail_frames frames' time: the recording may hold the steps between
      // the frames too (motus render records them for trails), so the trail follows the path that
      // was simulated, bounces included, not straight lines from frame to frame.
      size_t first = index > static_cast<size_t>(options.trail_frames) ? index - static_cast<size_t>(options.trail_frames) : 0;
      if (options.frame_interval > 0) {
        const double from = rec.times[index] - options.trail_frames * options.frame_interval * (1 + 1e-9);
        first = static_cast<size_t>(std::lower_bound(rec.times.begin(), rec.times.begin() + static_cast<long>(index), from) -
                                    rec.times.begin());
      }
      for (size_t i = first; i <= index; ++i) frame.trail.push_back(std::span<const double>(rec.states[i]).first(half));
    }
    draw_mechanical(canvas, v, scene, frame, camera, options);
    // A length to read the picture by, where the view is a flat map in metres (not the pendulum's
    // or the 1-D spring's own layouts, which draw their own).
    if (options.overlay && scene.mechanical->dimensions == 2) draw_scale_bar(canvas, v, camera);
    if (index < rec.energies.size()) {
      overlay.energy_in_joules = rec.energies.front() == 0;  // (nothing to divide by: the change itself)
      overlay.energy_drift = (rec.energies[index] - rec.energies.front()) /
                             (overlay.energy_in_joules ? 1.0 : std::abs(rec.energies.front()));
    }
  } else {
    const size_t count = rec.states[index].size();
    const auto labels = series_labels(scene, count);
    overlay.time_unit = labels.time_unit;
    if (count == 3)
      draw_trajectory_3d(canvas, v, rec, index, camera, labels, options);
    else
      draw_time_series(canvas, v, rec, index, labels, options);
  }
  if (options.overlay) draw_overlay(canvas, v, overlay);
}

}  // namespace motus::render
