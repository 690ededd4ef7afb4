#include "motus/compare/initial_overlap.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace motus::compare {

InitialOverlap initial_overlap(const MechanicalDescription& m) {
  InitialOverlap o;
  const int d = std::clamp(m.dimensions, 1, 3);
  const size_t n = m.bodies.size();
  auto x = [&](size_t i, int k) {
    const auto& p = m.bodies[i].position;
    return static_cast<size_t>(k) < p.size() ? p[static_cast<size_t>(k)] : 0.0;
  };
  // Of the contact distance (or radius): a position written to 7 digits, not a mistake (billiards's
  // rack, its balls touching to 10 digits, overlaps by 1.3e-8 of it).
  constexpr double kRounding = 1e-6;
  // Balls: a grid of cells 2·r_max wide, so that two balls that overlap are in neighbouring cells.
  double r_max = 0;
  for (const auto& b : m.bodies) r_max = std::max(r_max, b.radius);
  if (r_max > 0 && std::isfinite(r_max)) {
    const double cell = 2 * r_max;
    using Key = std::array<std::int64_t, 3>;
    auto cell_of = [&](double c) {
      const double f = std::floor(c / cell);
      return static_cast<std::int64_t>(std::clamp(std::isfinite(f) ? f : 0.0, -4e18, 4e18));
    };
    std::vector<std::pair<Key, int>> cells;
    cells.reserve(n);
    for (size_t i = 0; i < n; ++i) {
      if (!(m.bodies[i].radius > 0)) continue;
      Key key{0, 0, 0};
      for (int k = 0; k < d; ++k) key[static_cast<size_t>(k)] = cell_of(x(i, k));
      cells.push_back({key, static_cast<int>(i)});
    }
    std::sort(cells.begin(), cells.end());
    auto by_key = [](const std::pair<Key, int>& a, const Key& b) { return a.first < b; };
    for (const auto& [key, i] : cells) {
      const int reach = d == 1 ? 1 : d == 2 ? 9 : 27;
      for (int c = 0; c < reach; ++c) {
        Key near = key;
        int code = c;
        for (int k = 0; k < d; ++k, code /= 3) near[static_cast<size_t>(k)] += code % 3 - 1;
        // (The first axis's neighbours by the sort order: lower_bound from the cell before.)
        if (d == 1) near[0] = key[0] - 1;
        auto at = std::lower_bound(cells.begin(), cells.end(), near, by_key);
        const Key last = d == 1 ? Key{key[0] + 1, 0, 0} : near;
        for (; at != cells.end() && at->first <= last; ++at) {
          const int k = at->second;
          if (k <= i) continue;
          const size_t a = static_cast<size_t>(i), b = static_cast<size_t>(k);
          double s = 0;
          for (int q = 0; q < d; ++q) s += (x(a, q) - x(b, q)) * (x(a, q) - x(b, q));
          const double R = m.bodies[a].radius + m.bodies[b].radius;
          const double depth = R - std::sqrt(s);
          if (!(depth > kRounding * R)) continue;
          ++o.pairs;
          // (The deepest; of equally deep ones the first by index, whatever the grid's order.)
          if (depth > o.pair_depth || (depth == o.pair_depth && std::pair(i, k) < std::pair(o.pair_a, o.pair_b)))
            o.pair_depth = depth, o.pair_a = i, o.pair_b = k;
        }
      }
    }
  }
  // Walls: past a plane's surface, through a box's faces or out of it, within a segment's radius.
  for (size_t i = 0; i < n; ++i) {
    const double r = m.bodies[i].radius;
    const double tolerance = kRounding * (r > 0 ? r : 1);
    double deepest = 0;
    std::string wall;
    bool outside = false;
    for (size_t j = 0; j < m.colliders.planes.size(); ++j) {
      const auto& p = m.colliders.planes[j];
      double along = 0, norm = 0;
      for (int k = 0; k < d; ++k) {
        along += p.normal[static_cast<size_t>(k)] * x(i, k);
        norm += p.normal[static_cast<size_t>(k)] * p.normal[static_cast<size_t>(k)];
      }
      norm = std::sqrt(norm);
      if (!(norm > 0)) continue;
      const double depth = r - (along - p.offset) / norm;
      if (depth > tolerance && depth > deepest) deepest = depth, wall = "plane " + std::to_string(j), outside = false;
    }
    for (size_t j = 0; j < m.colliders.boxes.size(); ++j) {
      const auto& b = m.colliders.boxes[j];
      double depth = -1;
      bool beyond = false;
      for (int k = 0; k < d; ++k) {
        const double c = x(i, k), low = b.min[static_cast<size_t>(k)], high = b.max[static_cast<size_t>(k)];
        depth = std::max({depth, r - (c - low), r - (high - c)});
        beyond = beyond || c < low || c > high;
      }
      if (depth > tolerance && depth > deepest) deepest = depth, wall = "box " + std::to_string(j), outside = beyond;
    }
    if (d == 2)
      for (size_t j = 0; j < m.colliders.segments.size(); ++j) {
        if (!(r > 0)) continue;
        const auto& s = m.colliders.segments[j];
        const double ax = s.b[0] - s.a[0], ay = s.b[1] - s.a[1];
        const double px = x(i, 0) - s.a[0], py = x(i, 1) - s.a[1];
        const double ll = ax * ax + ay * ay;
        const double t = ll > 0 ? std::clamp((px * ax + py * ay) / ll, 0.0, 1.0) : 0.0;
        const double depth = r - std::hypot(px - t * ax, py - t * ay);
        if (depth > tolerance && depth > deepest) deepest = depth, wall = "segment " + std::to_string(j), outside = false;
      }
    if (wall.empty()) continue;
    ++o.into_walls;
    if (deepest > o.wall_depth)
      o.wall_depth = deepest, o.wall_body = static_cast<int>(i), o.wall = wall, o.outside_box = outside;
  }
  return o;
}

std::string initial_overlap_note(const InitialOverlap& o, bool penetration_column) {
  if (!o.any()) return "";
  auto more = [](long count, const char* one, const char* many) {
    return count > 1 ? fmt::format(" (and {} more {})", count - 1, count - 1 == 1 ? one : many) : std::string();
  };
  std::string text;
  if (o.pairs > 0)
    text = fmt::format("bodies {} and {} start overlapping by {:.3g} m{}", o.pair_a, o.pair_b, o.pair_depth,
                       more(o.pairs, "pair", "pairs"));
  if (o.into_walls > 0) {
    if (!text.empty()) text += "; ";
    text += o.outside_box ? fmt::format("body {} starts outside {}, {:.3g} m into its wall", o.wall_body, o.wall, o.wall_depth)
                          : fmt::format("body {} starts {:.3g} m into {}", o.wall_body, o.wall_depth, o.wall);
    text += more(o.into_walls, "body", "bodies");
  }
  const bool one = o.pairs == 0 && o.into_walls == 1;
  text += o.pairs == 0 ? (one && o.outside_box ? "; motus moves it into the box"
                                               : one ? "; motus moves it out of the wall" : "; motus moves them out of the walls")
          : o.into_walls == 0 ? "; motus moves them apart"
                              : "; motus moves them apart and out of the walls";
  text += " before the first step";
  if (penetration_column) text += ", and the penetration column counts that start";
  return text;
}

std::string initial_overlap_note(const SceneDescription& scene, bool penetration_column) {
  return scene.mechanical ? initial_overlap_note(initial_overlap(*scene.mechanical), penetration_column) : "";
}


}  // namespace motus::compare
