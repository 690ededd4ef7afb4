// coarse_resolution (scene_file.hpp): whether doubles are fine enough where the bodies are for the
// scene's moves at the step run, a check on a loaded scene and not part of reading one; it names the
// fields of the scene this thread loaded last, kept here in a thread_local copy.
#include "motus/scene_file/position_resolution.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "motus/message_number.hpp"
#include "motus/scene_error.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/vector.hpp"

namespace motus {
namespace {

// Where the bodies are too far for the scene's moves (coarse_resolution), and what makes the moves.
struct CoarsePositions {
  enum class Where { body, plane, box };
  Where where = Where::body;  // what puts the bodies that far
  size_t index = 0;           // the body's, or the wall's among the scene's planes or boxes
  double far = 0;             // m from the origin (the largest coordinate) that the bodies are, or are kept
  double spacing = 0;         // m between neighbouring doubles there
  double move = 0;            // m: the scene's largest move in a step
  size_t mover = 0;           // the body that makes it
  double acceleration = 0;    // m/s²: the mover's at the start, when its move is its speed after `duration` under it
  double duration = 0;        // s: the run's
};

// The description has no room for where its bodies and walls came from, and the commands check the
// positions after loading, at the step they run: the loader keeps the fields of the scene it loaded
// last on this thread, with what tells that scene from another (its bodies' storage and the counts).
struct LoadedFields {
  const BodyDescription* bodies = nullptr;
  size_t count = 0, planes = 0, boxes = 0;
  MechanicalFields fields;
};
thread_local LoadedFields loaded_fields;

}  // namespace

void remember_fields(const MechanicalDescription& m, MechanicalFields fields) {
  loaded_fields = {m.bodies.data(), m.bodies.size(), m.colliders.planes.size(), m.colliders.boxes.size(), std::move(fields)};
}

namespace {

const MechanicalFields* fields_of(const MechanicalDescription& m) {
  const LoadedFields& l = loaded_fields;
  return l.bodies == m.bodies.data() && l.count == m.bodies.size() && l.planes == m.colliders.planes.size() &&
                 l.boxes == m.colliders.boxes.size()
             ? &l.fields
             : nullptr;
}

// What makes the scene's largest move: "its fastest speed times dt = 0.01 s", or a body's speed after
// the run under its acceleration at the start.
std::string why_it_moves(const CoarsePositions& c, double dt) {
  const std::string step = "dt = " + message_number(dt, 6) + " s";
  return c.acceleration > 0 ? "body " + std::to_string(c.mover) + "'s speed after " + message_number(c.duration, 6) +
                                  " s at " + message_number(c.acceleration, 6) + " m/s², times " + step
                            : "its fastest speed times " + step;
}

// The error for `c`, named by the field that puts the bodies there: a listed body's position; a
// generator's origin, when that alone is too far, else its spacing; a plane's offset; a box's corner
// nearest the origin. (`fields`: none for a description the loader did not make.)
SceneError coarse_positions_error(const MechanicalDescription& m, const MechanicalFields* fields, const CoarsePositions& c,
                                  double dt) {
  const std::string why = why_it_moves(c, dt);
  const std::string words = "positions are " + message_number(c.spacing, 6) +
                            " m apart, too coarse for the scene's moves of " + message_number(c.move, 6) + " m a step (" +
                            why + ")";
  const std::string far = message_number(c.far, 6);
  const std::string rounding = ": they would move by rounding, or not at all; ";
  if (c.where == CoarsePositions::Where::body) {
    const size_t i = c.index;
    if (fields)
      for (const auto& g : fields->generated) {
        if (i < g.first || i >= g.end) continue;
        // The origin alone that far is the origin's fault; else the generator's size took them there.
        double origin = 0;
        for (int k = 0; k < m.dimensions; ++k) origin = std::max(origin, std::abs(g.origin[static_cast<size_t>(k)]));
        const bool by_origin = std::nextafter(origin, INFINITY) - origin > 1e-3 * c.move;
        return SceneError(g.name + "." + (by_origin ? std::string("origin") : g.spacing_key),
                          "puts body " + std::to_string(i) + " at " + far + " m, where " + words + rounding +
                              (by_origin ? "an origin nearer 0" : "a smaller " + g.spacing_key));
      }
    return SceneError("bodies[" + std::to_string(i) + "].position",
                      "at " + far + " m " + words + ": its bodies would move by rounding, or not at all; move the scene "
                                                    "nearer the origin");
  }
  const bool plane = c.where == CoarsePositions::Where::plane;
  const size_t j = c.index;
  std::string field = plane ? "colliders (plane " + std::to_string(j) + ")" : "colliders (box " + std::to_string(j) + ")";
  if (fields) {
    const size_t generated = plane ? fields->planes_generated : fields->boxes_generated;
    const auto& paths = plane ? fields->plane_paths : fields->box_paths;
    if (j < generated && !fields->generated.empty()) field = fields->generated.front().name + ".origin";  // (a lattice's box)
    if (j >= generated && j - generated < paths.size()) field = paths[j - generated];
  }
  if (plane) {
    if (field.starts_with("colliders[")) field += ".offset";
  } else {
    // The box's corner nearest the origin: its min where that is above 0, its max where below.
    const auto& box = m.colliders.boxes[j];
    bool by_min = true;
    double nearest = -1;
    for (int k = 0; k < m.dimensions; ++k) {
      const double x = std::clamp(0.0, box.min[static_cast<size_t>(k)], box.max[static_cast<size_t>(k)]);
      if (std::abs(x) > nearest) nearest = std::abs(x), by_min = x > 0;
    }
    if (field.starts_with("colliders[")) field += by_min ? ".min" : ".max";
  }
  return SceneError(field, std::string("the ") + (plane ? "plane" : "box") + " keeps bodies " + far +
                               " m or more out, where " + words + rounding + "move it nearer the origin");
}

// |x|, scaled by its largest component first (m g of 1e307 kg squares past every double).
double length(const double* x, int d) {
  double largest = 0, sum = 0;
  for (int k = 0; k < d; ++k) largest = std::max(largest, std::abs(x[k]));
  if (!(largest > 0) || !std::isfinite(largest)) return largest;
  for (int k = 0; k < d; ++k) sum += (x[k] / largest) * (x[k] / largest);
  return largest * std::sqrt(sum);
}

// The scene's largest move in a step (c.move, c.mover, c.acceleration, c.duration); nothing when a
// move is past every double or a force is not a number (other checks say why). The moves are the
// bodies' speeds times dt, at the start and after the run's `duration` under the acceleration the
// forces give at the start: the largest a step makes then, had they held. (A body at rest under
// gravity makes none at first and still moves; a run of dt = 1e-6 s from rest near the origin, whose
// first steps move by 1e-12 m, is one.)
std::optional<CoarsePositions> largest_move(const MechanicalDescription& m, double dt, double duration) {
  const size_t n = m.bodies.size();
  const int d = m.dimensions;
  const auto size = static_cast<Eigen::Index>(n) * d;
  // Each body's acceleration at the start, from every force (a pinned body is held: none).
  Vector a = Vector::Zero(size);
  if (m.forces.acts() && n > 0) {
    ForceSet forces = m.forces;
    if (n > 4096) forces.mutual_gravity.clear();
    Vector masses(static_cast<Eigen::Index>(n)), x(size), v(size);
    for (size_t i = 0; i < n; ++i) {
      masses[static_cast<Eigen::Index>(i)] = m.bodies[i].mass;
      for (int k = 0; k < d; ++k) {
        x[static_cast<Eigen::Index>(i) * d + k] = m.bodies[i].position[static_cast<size_t>(k)];
        v[static_cast<Eigen::Index>(i) * d + k] = m.bodies[i].velocity[static_cast<size_t>(k)];
      }
    }
    forces.add_forces(0, d, masses, x, v, a);
    for (size_t i = 0; i < n; ++i) a.segment(static_cast<Eigen::Index>(i) * d, d) /= m.bodies[i].mass;
    for (const auto& pin : m.pins)
      if (pin.body >= 0 && static_cast<size_t>(pin.body) < n) a.segment(static_cast<Eigen::Index>(pin.body) * d, d).setZero();
  }
  CoarsePositions c;
  for (size_t i = 0; i < n; ++i) {
    const double* accel = a.data() + static_cast<Eigen::Index>(i) * d;
    double later[3] = {0, 0, 0};
    for (int k = 0; k < d; ++k) later[k] = m.bodies[i].velocity[static_cast<size_t>(k)] + accel[k] * duration;
    const double by_speed = length(m.bodies[i].velocity.data(), d) * dt, by_force = length(later, d) * dt;
    // (A move past every double, or a force that is not a number: no claim; other checks say why.)
    if (!std::isfinite(by_speed) || !std::isfinite(by_force)) return std::nullopt;
    if (std::max(by_speed, by_force) > c.move) {
      c.move = std::max(by_speed, by_force);
      c.mover = i;
      c.acceleration = by_force > by_speed ? length(accel, d) : 0;
    }
  }
  c.duration = duration;
  return c;
}

// Where the bodies are (c.far, c.where, c.index): the farthest one's largest coordinate, or where a
// wall keeps them if that is farther.
void find_farthest(const MechanicalDescription& m, CoarsePositions& c) {
  const int d = m.dimensions;
  for (size_t i = 0; i < m.bodies.size(); ++i)
    for (double x : m.bodies[i].position)
      if (std::abs(x) > c.far) c.far = std::abs(x), c.where = CoarsePositions::Where::body, c.index = i;
  // Walls keep the bodies away from the origin: on a plane's free side when that side is away from
  // it (there every point has a coordinate of at least offset / Σ|n_k|), inside every box.
  for (size_t j = 0; j < m.colliders.planes.size(); ++j) {
    const auto& plane = m.colliders.planes[j];
    double l1 = 0;
    for (int k = 0; k < d; ++k) l1 += std::abs(plane.normal[static_cast<size_t>(k)]);
    if (plane.offset > 0 && l1 > 0 && plane.offset / l1 > c.far)
      c.far = plane.offset / l1, c.where = CoarsePositions::Where::plane, c.index = j;
  }
  for (size_t j = 0; j < m.colliders.boxes.size(); ++j) {
    const auto& box = m.colliders.boxes[j];
    for (int k = 0; k < d; ++k) {
      const double nearest = std::abs(std::clamp(0.0, box.min[static_cast<size_t>(k)], box.max[static_cast<size_t>(k)]));
      if (nearest > c.far) c.far = nearest, c.where = CoarsePositions::Where::box, c.index = j;
    }
  }
}

// Whether the positions are too coarse for the moves `c` (largest_move, find_farthest): spacing set.
bool too_coarse_for_moves(CoarsePositions& c) {
  if (!(c.move > 0) || !std::isfinite(c.far)) return false;  // (nothing moves; or no position to judge)
  c.spacing = std::nextafter(c.far, INFINITY) - c.far;
  return c.spacing > 1e-3 * c.move;
}

// The contacts' check (coarse_resolution in scene_file.hpp) on the moves `c`: what is wrong, or nothing.
std::optional<std::string> too_coarse_for_contacts(const MechanicalDescription& m, const CoarsePositions& c, double dt) {
  double smallest = INFINITY;
  size_t balls = 0;
  for (const auto& body : m.bodies)
    if (body.radius > 0) ++balls, smallest = std::min(smallest, body.radius);
  const Colliders& walls = m.colliders;
  const bool any_wall = !walls.planes.empty() || !walls.boxes.empty() || !walls.segments.empty();
  if (balls < 2 && !(balls == 1 && any_wall)) return std::nullopt;  // no contact to resolve
  if (!(c.move > 0)) return std::nullopt;
  const double reach = c.far + c.move;
  if (!std::isfinite(reach)) return std::nullopt;  // (the position check, or the run, says why)
  const double spacing = std::nextafter(reach, INFINITY) - reach;
  if (spacing <= kContactResolution * smallest) return std::nullopt;
  return "a step takes the bodies " + message_number(reach, 6) + " m from the origin (" + why_it_moves(c, dt) +
         ": a move of " + message_number(c.move, 6) + " m), where positions are " + message_number(spacing, 6) +
         " m apart, more than a thousandth of the smallest ball's radius (" + message_number(smallest, 6) +
         " m): too coarse to resolve its contacts at their time within the step; a smaller dt";
}

}  // namespace

CoarseResolution coarse_resolution(const SceneDescription& scene, double dt) {
  if (!scene.mechanical) return {};
  const MechanicalDescription& m = *scene.mechanical;
  // (The forces at the start evaluated once, for both checks: mutual gravity is every pair.)
  auto moved = largest_move(m, dt, scene.duration);
  if (!moved) return {};
  CoarsePositions c = *moved;
  find_farthest(m, c);
  if (too_coarse_for_moves(c)) return {coarse_positions_error(m, fields_of(m), c, dt), std::nullopt};
  return {std::nullopt, too_coarse_for_contacts(m, c, dt)};
}

}  // namespace motus
