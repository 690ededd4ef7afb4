#pragma once
// Which of several runs of one scene (a comparison's engines) one view can show together. A run
// that blew up — its bodies thrown a thousand kilometres, still finite — would shrink the others to a
// dot in a view fitted to every run. Header only, and with nothing of OpenGL: the drawn frames
// (render's in_a_shared_view) and the report's replay (compare/replay.cpp) judge by the same rule.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "motus/scene.hpp"

namespace motus::render {

// How far from the reference run's middle another run's bodies may go, in the reference's reaches.
constexpr double kFarthestInView = 4;

// `ran[e]` says which of the runs ran; of those, the run `reference` is always in view, and each other
// one whose bodies stay within kFarthestInView times the reference's reach (half its widest extent,
// or the largest body's radius) from the reference's middle, in every coordinate of every state.
// `states(e, visit)` calls visit(x) for each recorded state of run e, where x[i·d + k] is body i's
// coordinate k (i < bodies, k < d). A NaN is out of view; when the reference's own bodies are past
// every double there is no scale to judge by, and `ran` is returned as it is.
template <class States>
std::vector<bool> in_a_shared_view(int d, std::size_t bodies, double largest_radius, const States& states,
                                   std::size_t reference, std::vector<bool> ran) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (reference >= ran.size() || d < 1 || d > 3) return ran;
  const auto du = static_cast<std::size_t>(d);
  double low[3] = {kInf, kInf, kInf}, high[3] = {-kInf, -kInf, -kInf};
  states(reference, [&](const auto& x) {
    for (std::size_t i = 0; i < bodies; ++i)
      for (std::size_t k = 0; k < du; ++k) {
        const double c = x[i * du + k];
        low[k] = std::min(low[k], c), high[k] = std::max(high[k], c);
      }
  });
  double middle[3] = {0, 0, 0}, reach = 0;
  for (std::size_t k = 0; k < du; ++k) middle[k] = (low[k] + high[k]) / 2, reach = std::max(reach, (high[k] - low[k]) / 2);
  if (!std::isfinite(reach)) return ran;
  reach = std::max({reach, largest_radius, 1e-9});  // (a ball at rest has a size)
  for (std::size_t e = 0; e < ran.size(); ++e) {
    if (!ran[e] || e == reference) continue;
    bool inside = true;
    states(e, [&](const auto& x) {
      for (std::size_t i = 0; i < bodies && inside; ++i)
        for (std::size_t k = 0; k < du; ++k)
          if (!(std::abs(x[i * du + k] - middle[k]) <= kFarthestInView * reach)) inside = false;  // (NaN too)
    });
    ran[e] = inside;
  }
  return ran;
}

// The same for runs of a mechanical scene: its dimensions, its bodies, its largest radius (`ran` as it
// is for any other scene).
template <class States>
std::vector<bool> in_a_shared_view(const SceneDescription& scene, const States& states, std::size_t reference,
                                   std::vector<bool> ran) {
  if (!scene.mechanical) return ran;
  const auto& m = *scene.mechanical;
  double largest_radius = 0;
  for (const auto& body : m.bodies) largest_radius = std::max(largest_radius, body.radius);
  return in_a_shared_view(m.dimensions, m.bodies.size(), largest_radius, states, reference, std::move(ran));
}

}  // namespace motus::render
