#pragma once
// The yardstick: one implementation of every metric, applied to every engine's
// snapshots alike — energies from motus's own force laws, momenta, the deepest
// interpenetration, the worst stick, and the distance from motus's trajectory and from
// the scene's analytic solution.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "motus/compare/backends/backend.hpp"
#include "motus/scene.hpp"
#include "motus/systems/mechanical_system.hpp"

namespace motus::compare {

struct MetricsRow {
  double t = 0;
  double kinetic = 0, potential = 0, total = 0;
  std::vector<double> momentum;          // d components
  std::vector<double> angular_momentum;  // about the origin: 1 component in 2-D, 3 in 3-D, none in 1-D
  double penetration = 0;       // the deepest overlap of two balls or of a ball and a wall, m
  double constraint_error = 0;  // the largest relative stick-length error
  double from_motus = 0;        // the largest distance of a body from where motus has it, m
  double from_exact = -1;       // the same from the analytic solution; −1 when the scene has none
};

// The larger of a running maximum and a new value, where a value that is not a number (a run that
// blew up, or a student's code that returned NaN) is the worst of all: std::max(worst, NaN) would
// keep `worst`, and a broken run would read as a perfect one.
inline double worse(double worst, double x) { return std::isnan(x) ? INFINITY : std::max(worst, x); }

class Metrics {
public:
  explicit Metrics(const SceneDescription& scene);

  // `motus` is motus's snapshot at the same time (nullptr: not known).
  MetricsRow measure(const Snapshot& s, const Snapshot* motus) const;
  // The largest relative stick-length error in s (0 without sticks; +∞ once not finite).
  double stick_error(const Snapshot& s) const;
  // How far the deepest ball is inside another or a wall at x (m; 0 when none is; +∞ once not finite).
  double deepest_penetration(const std::vector<double>& x) const;
  // Whether anything can overlap: a ball and a wall, or two balls.
  bool has_contacts() const;

private:

  const SceneDescription& scene_;
  MechanicalSystem system_;
  int d_;
  std::vector<double> radius_;
  double max_radius_ = 0;
  std::vector<int> balls_;
  // A scratch grid for the penetration check (sorted once per measurement).
  mutable std::vector<std::pair<long, int>> cells_;
};

}  // namespace motus::compare
