#include "motus/scene_file/scene_file.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <algorithm>

#include "motus/scene_file/json_fields.hpp"
#include "motus/ball_lattice.hpp"
#include "motus/scene_generators.hpp"
#include "motus/exact/exact_solution.hpp"
#include "motus/integrate/integrator_catalog.hpp"
#include "motus/message_number.hpp"
#include "motus/scene_error.hpp"
#include "motus/systems/system_catalog.hpp"
#include "motus/scene_file/printable_text.hpp"
#include "motus/scene_file/scene_overrides.hpp"
#include "motus/scene_file/spelling.hpp"
#include "motus/scene_file/strict_json.hpp"
#include "motus/scene_file/position_resolution.hpp"
#include "motus/scene_file/strict_json_sax.hpp"
#include "motus/scene_file/equations_system.hpp"

namespace motus {
namespace {

std::array<double, 3> padded(const std::vector<double>& v) {
  std::array<double, 3> a{0, 0, 0};
  for (size_t k = 0; k < v.size() && k < 3; ++k) a[k] = v[k];
  return a;
}

int body_index(JsonFields& f, const std::string& key, size_t bodies) {
  const long i = f.integer(key);
  if (i < 0 || i >= static_cast<long>(bodies))
    f.fail(key, "must name a body: 0 to " + std::to_string(static_cast<long>(bodies) - 1) + " (got " +
                    std::to_string(i) + ")");
  return static_cast<int>(i);
}

void read_force(JsonFields& f, int d, size_t bodies, ForceSet& forces) {
  const std::string type = f.string("type");
  if (type == "gravity") {
    forces.gravity.push_back({padded(f.numbers("g", d))});
  } else if (type == "spring") {
    Spring s;
    s.a = body_index(f, "a", bodies);
    if (f.has("b") == f.has("anchor")) f.fail("b", "a spring needs exactly one of \"b\" (a body) and \"anchor\" (a point)");
    if (f.has("b")) {
      s.b = body_index(f, "b", bodies);
      if (s.b == s.a) f.fail("b", "a spring needs two different bodies");
    } else {
      s.anchor = padded(f.numbers("anchor", d));
    }
    s.stiffness = f.non_negative("stiffness");
    s.rest_length = f.non_negative("rest_length", 0);
    s.damping = f.non_negative("damping", 0);
    forces.springs.push_back(s);
  } else if (type == "drag") {
    LinearDrag g;
    g.coefficient = f.non_negative("coefficient");
    g.body = f.has("body") ? body_index(f, "body", bodies) : -1;
    forces.drag.push_back(g);
  } else if (type == "central_gravity") {
    CentralGravity g;
    g.mu = f.positive("mu");
    g.centre = padded(f.numbers("centre", d, std::vector<double>(static_cast<size_t>(d), 0.0)));
    g.softening = f.non_negative("softening", 0);
    g.body = f.has("body") ? body_index(f, "body", bodies) : -1;
    forces.central_gravity.push_back(g);
  } else if (type == "mutual_gravity") {
    MutualGravity g;
    g.G = f.positive("G");
    g.softening = f.non_negative("softening", 0);
    forces.mutual_gravity.push_back(g);
  } else if (type == "pendulum") {
    if (d != 1) f.fail("type", "a pendulum force acts on a 1-D body (its angle); this scene is " + std::to_string(d) + "-D");
    PendulumTorque p;
    p.body = f.has("body") ? body_index(f, "body", bodies) : 0;
    p.g = f.positive("g", 9.81);
    p.length = f.positive("length");
    forces.pendulums.push_back(p);
  } else {
    f.fail("type", unknown_one_of("force", type, {"gravity", "spring", "drag", "central_gravity", "mutual_gravity", "pendulum"}));
  }
  f.reject_unknown();
}

double restitution(JsonFields& f, const std::string& key) {
  const double e = f.number(key, 1.0);
  if (e < 0 || e > 1) f.fail(key, "must be between 0 and 1 (got " + nlohmann::json(e).dump() + ")");
  return e;
}

// Generated bodies are checked like written ones: a spacing or size that overflows gives
// positions at infinity, which no step could use.
void check_generated(JsonFields& f, const MechanicalDescription& m, size_t first, const std::string& key) {
  for (size_t i = first; i < m.bodies.size(); ++i)
    for (size_t k = 0; k < m.bodies[i].position.size(); ++k)
      if (!std::isfinite(m.bodies[i].position[k]) || !std::isfinite(m.bodies[i].velocity[k]))
        f.fail(key, "the generated body " + std::to_string(i) + " is not at a finite position (" + key +
                        " is too large for double precision)");
}

// A cloth's or a rope's sticks are as long as the particles are apart where they were made:
// `spacing` (√2 times it across a cloth's squares). Far enough from 0, double precision cannot
// hold that distance (at 1e17 m, positions are 16 m apart) and a stick would be made shorter,
// or of length 0; and anywhere, a spacing whose square is not a normal double (1e-160 m: 1e-320)
// gives lengths that are not it. `at_zero`: the same generator's sticks with its origin at 0, which
// tell the two apart (the message named the origin, [0, 0], for a segment_length of 1e-160 m).
bool sticks_as_made(const MechanicalDescription& m, size_t first_stick, double spacing) {
  for (size_t s = first_stick; s < m.sticks.size(); ++s) {
    const double length = m.sticks[s].length;
    if (!(length >= (1 - 1e-6) * spacing && length <= (1 + 1e-6) * std::sqrt(2.0) * spacing)) return false;
  }
  return true;
}

// A generator's particles and sticks made alone, with its origin at 0 (check_generated_sticks'
// `at_zero`): `add` is add_cloth or add_rope.
template <class Generator, class Add>
MechanicalDescription built_at_origin(const MechanicalDescription& m, Generator generator, Add add) {
  MechanicalDescription alone;
  alone.dimensions = m.dimensions;
  generator.origin = {0, 0, 0};
  add(alone, generator);
  return alone;
}

template <class AtZero>
void check_generated_sticks(JsonFields& f, const MechanicalDescription& m, size_t first_stick, double spacing,
                            const std::string& spacing_key, AtZero at_zero) {
  if (sticks_as_made(m, first_stick, spacing)) return;
  if (!sticks_as_made(at_zero(), 0, spacing)) {
    const bool small = spacing < 1;
    f.fail(spacing_key, "is too " + std::string(small ? "small" : "large") + " for double precision: a stick's length " +
                            "comes from a squared distance, and (" + message_number(spacing, 6) + " m)² is " +
                            (small ? "below the smallest normal double (2.2e-308)" : "past the largest double (1.8e308)"));
  }
  f.fail("origin", "is too far from 0 for a " + spacing_key + " of " + nlohmann::json(spacing).dump() +
                       " m: double precision cannot hold the particles that far apart there");
}

void read_lattice(JsonFields f, MechanicalDescription& m, MechanicalFields& fields) {
  BallLattice lattice;
  lattice.count = f.integer("count");
  if (lattice.count < 1 || lattice.count > kMaxBodies)
    f.fail("count", "must be from 1 to " + std::to_string(kMaxBodies) + ", the limit of a scene's bodies (got " +
                        std::to_string(lattice.count) + ")");
  lattice.spacing = f.positive("spacing", lattice.spacing);
  lattice.radius = f.positive("radius", lattice.radius);
  // (Touching balls packed wall to wall are jammed: each contact passes its push on to the next, and back
  // from the walls, all at one instant, without end.)
  if (2 * lattice.radius >= lattice.spacing)
    f.fail("radius", "balls of this radius touch or overlap at this spacing (the lattice would be jammed): it must be "
                     "less than spacing/2");
  lattice.mass = f.positive("mass", lattice.mass);
  lattice.speed = f.non_negative("speed", lattice.speed);
  const long seed = f.integer("seed", 1);
  if (seed < 0) f.fail("seed", "must be >= 0 (got " + std::to_string(seed) + ")");
  lattice.seed = static_cast<std::uint64_t>(seed);
  lattice.restitution = restitution(f, "restitution");
  lattice.origin = padded(f.numbers("origin", m.dimensions, std::vector<double>(static_cast<size_t>(m.dimensions), 0.0)));
  lattice.container = f.boolean("container", true);
  f.reject_unknown();
  const size_t first = m.bodies.size();
  add_ball_lattice(m, lattice);
  check_generated(f, m, first, "spacing");
  fields.generated.push_back({first, m.bodies.size(), "lattice", "spacing", lattice.origin});
}

int small_count(JsonFields& f, const std::string& key, long fallback, long max) {
  const long n = f.integer(key, fallback);
  if (n < 1 || n > max) f.fail(key, "must be from 1 to " + std::to_string(max) + " (got " + std::to_string(n) + ")");
  return static_cast<int>(n);
}

void read_cloth(JsonFields f, MechanicalDescription& m, MechanicalFields& fields) {
  ClothGenerator cloth;
  cloth.rows = small_count(f, "rows", cloth.rows, 1000);
  cloth.columns = small_count(f, "columns", cloth.columns, 1000);
  if (static_cast<long>(cloth.rows) * cloth.columns > kMaxClothParticles)
    f.fail("columns", std::to_string(cloth.rows) + " x " + std::to_string(cloth.columns) + " particles is more than " +
                          std::to_string(kMaxClothParticles) + " (500 x 500), the limit of a cloth");
  cloth.spacing = f.positive("spacing", cloth.spacing);
  cloth.mass = f.positive("mass", cloth.mass);
  cloth.origin = padded(f.numbers("origin", m.dimensions, std::vector<double>(static_cast<size_t>(m.dimensions), 0.0)));
  cloth.shear = f.boolean("shear", cloth.shear);
  cloth.pin = f.string("pin", cloth.pin);
  cloth.plane = f.string("plane", cloth.plane);
  f.reject_unknown();
  const size_t first = m.bodies.size(), first_stick = m.sticks.size();
  add_cloth(m, cloth);  // SceneError("cloth.pin", ...) for values it cannot build
  check_generated(f, m, first, "spacing");
  check_generated_sticks(f, m, first_stick, cloth.spacing, "spacing", [&] { return built_at_origin(m, cloth, add_cloth); });
  fields.generated.push_back({first, m.bodies.size(), "cloth", "spacing", cloth.origin});
}

void read_rope(JsonFields f, MechanicalDescription& m, MechanicalFields& fields) {
  RopeGenerator rope;
  rope.segments = small_count(f, "segments", rope.segments, 100000);
  rope.segment_length = f.positive("segment_length", rope.segment_length);
  rope.mass = f.positive("mass", rope.mass);
  const std::vector<double> zero(static_cast<size_t>(m.dimensions), 0.0);
  rope.origin = padded(f.numbers("origin", m.dimensions, zero));
  std::vector<double> along = zero;
  along[0] = 1;
  rope.direction = padded(f.numbers("direction", m.dimensions, along));
  rope.pin_first = f.boolean("pin_first", rope.pin_first);
  f.reject_unknown();
  const size_t first = m.bodies.size(), first_stick = m.sticks.size();
  add_rope(m, rope);
  check_generated(f, m, first, "segment_length");
  check_generated_sticks(f, m, first_stick, rope.segment_length, "segment_length", [&] { return built_at_origin(m, rope, add_rope); });
  fields.generated.push_back({first, m.bodies.size(), "rope", "segment_length", rope.origin});
}

void read_collider(JsonFields& f, int d, Colliders& colliders) {
  const std::string type = f.string("type");
  if (type == "plane") {
    PlaneCollider p;
    // Stored as a unit normal (and the offset divided alike), so that every reader of the scene
    // — engine, peers, pictures — sees the same wall. Scaled by its largest component first: the
    // squared length of [0, 1e200] overflows, and of [0, 1e-200] is 0, though neither is zero.
    auto normal = f.numbers("normal", d);
    double largest = 0;
    for (double c : normal) largest = std::max(largest, std::abs(c));
    if (largest == 0) f.fail("normal", "must not be zero");
    double length2 = 0;
    for (double& c : normal) c /= largest, length2 += c * c;
    const double length = std::sqrt(length2);
    for (double& c : normal) c /= length;
    p.normal = padded(normal);
    p.offset = f.number("offset", 0) / largest / length;
    if (!std::isfinite(p.offset))
      f.fail("offset", "is too large for this normal (offset / |normal| must be a finite number of metres)");
    p.restitution = restitution(f, "restitution");
    colliders.planes.push_back(p);
  } else if (type == "box") {
    BoxCollider b;
    b.min = padded(f.numbers("min", d));
    b.max = padded(f.numbers("max", d));
    for (int k = 0; k < d; ++k)
      if (!(b.max[k] > b.min[k])) f.fail("max", "must be greater than min in every coordinate");
    b.restitution = restitution(f, "restitution");
    colliders.boxes.push_back(b);
  } else if (type == "segment") {
    if (d != 2) f.fail("type", "segments exist in 2-D scenes only; this scene is " + std::to_string(d) + "-D");
    SegmentCollider s;
    s.a = padded(f.numbers("a", d));
    s.b = padded(f.numbers("b", d));
    if (s.a == s.b) f.fail("b", "a segment needs two different end points");
    double length2 = 0;
    for (int k = 0; k < d; ++k) length2 += (s.b[k] - s.a[k]) * (s.b[k] - s.a[k]);
    if (!std::isfinite(length2) || length2 < 1e-200)  // (the time of impact divides by it)
      f.fail("b", "the segment's length must be between 1e-100 and about 1e154 m");
    s.restitution = restitution(f, "restitution");
    colliders.segments.push_back(s);
  } else {
    f.fail("type", unknown_one_of("collider", type, {"plane", "box", "segment"}));
  }
  f.reject_unknown();
}

double distance(const BodyDescription& a, const BodyDescription& b) {
  double s = 0;
  for (size_t k = 0; k < a.position.size(); ++k) s += (a.position[k] - b.position[k]) * (a.position[k] - b.position[k]);
  return std::sqrt(s);
}

// A spring of rest length L > 0 between two bodies at one point (or a body at its anchor) pushes
// along no direction: it held 5 J of energy and never moved. Refused, as a stick there without a length is.
void check_spring_has_a_direction(JsonFields& f, const std::vector<BodyDescription>& bodies, const Spring& s) {
  if (!(s.rest_length > 0) || !(s.stiffness > 0)) return;
  const auto& a = bodies[static_cast<size_t>(s.a)].position;
  bool same = true;
  for (size_t k = 0; k < a.size(); ++k)
    same = same && a[k] == (s.b >= 0 ? bodies[static_cast<size_t>(s.b)].position[k] : s.anchor[k]);
  if (same)
    f.fail("rest_length", s.b >= 0 ? "the two bodies start at the same point, where a spring of rest length > 0 has no "
                                     "direction to push them apart; move one"
                                   : "the body starts at the anchor, where a spring of rest length > 0 has no direction "
                                     "to push it; move it");
}

// Unsoftened gravity about a centre is infinite at the centre (and, in a double, near enough to it):
// the first step failed and blamed the step size.
void check_no_body_at_the_centre(JsonFields& f, const MechanicalDescription& m, const CentralGravity& g) {
  if (g.softening > 0) return;
  for (size_t i = 0; i < m.bodies.size(); ++i) {
    if (g.body >= 0 && static_cast<size_t>(g.body) != i) continue;
    double r2 = 0;
    bool at = true;
    for (int k = 0; k < m.dimensions; ++k) {
      r2 += (m.bodies[i].position[k] - g.centre[k]) * (m.bodies[i].position[k] - g.centre[k]);
      at = at && m.bodies[i].position[k] == g.centre[k];
    }
    if (!std::isfinite(g.mu * m.bodies[i].mass / (r2 * std::sqrt(r2))))
      f.fail("centre", "body " + std::to_string(i) + " starts " + (at ? "at the centre" : "so near the centre") +
                           ", where unsoftened gravity is infinite" + (at ? "" : " in a double") +
                           "; move it, or give the force a softening");
  }
}

// Unsoftened mutual gravity between two bodies at one point is infinite: refuse the scene
// (naming both, and the force by its place in "forces", its path) rather than let the first step
// fail and blame the step size.
void check_coincident_under_gravity(const MechanicalDescription& m, const std::vector<std::string>& mutual_gravity_paths) {
  for (size_t g = 0; g < m.forces.mutual_gravity.size(); ++g) {
    if (m.forces.mutual_gravity[g].softening > 0) continue;
    std::vector<size_t> order(m.bodies.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return m.bodies[a].position < m.bodies[b].position; });
    for (size_t k = 1; k < order.size(); ++k)
      if (m.bodies[order[k]].position == m.bodies[order[k - 1]].position) {
        const size_t a = std::min(order[k], order[k - 1]), b = std::max(order[k], order[k - 1]);
        throw SceneError(mutual_gravity_paths[g],
                         "bodies " + std::to_string(a) + " and " + std::to_string(b) +
                             " are at the same point, where unsoftened mutual gravity is infinite; move one, or give "
                             "the force a softening");
      }
  }
}

// A ball wider than a box along an axis can never be inside it: its walls push it back and forth
// without end, and the run failed with "more than N collisions in one step" (exit 1). The listed
// balls are checked (the generators size their own boxes to fit).
// (box_paths: the listed boxes' paths, "colliders[j]", the last of m's boxes.)
void check_balls_fit_their_boxes(const MechanicalDescription& m, size_t listed, const std::vector<std::string>& box_paths) {
  const size_t first = m.colliders.boxes.size() - box_paths.size();
  for (size_t i = 0; i < listed; ++i)
    for (size_t j = 0; j < box_paths.size(); ++j)
      for (int k = 0; k < m.dimensions; ++k) {
        const auto& box = m.colliders.boxes[first + j];
        const double width = box.max[k] - box.min[k], r = m.bodies[i].radius;
        // (One exactly as wide as the box touches both walls at once, and cannot move across it either.)
        if (2 * r >= width)
          throw SceneError("bodies[" + std::to_string(i) + "].radius",
                           "a ball of radius " + nlohmann::json(r).dump() + " does not fit in the box " + box_paths[j] +
                               " (its width along " + "xyz"[k] + " is " + nlohmann::json(width).dump() +
                               "; a ball must be narrower than its box)");
      }
}

// Two planes that face each other make a slot: a ball as wide as it, or wider, can never be inside
// (the run failed with "body 0 was touched 1100 times … give the balls more restitution", every
// restitution 1), and planes whose free sides do not meet leave no room for any body. As for boxes:
// the listed balls are checked. (plane_paths: the listed planes' paths, the last of m's planes.)
void check_bodies_fit_between_planes(const MechanicalDescription& m, size_t listed,
                                     const std::vector<std::string>& plane_paths) {
  const size_t first = m.colliders.planes.size() - plane_paths.size();
  for (size_t j = 0; j < plane_paths.size(); ++j)
    for (size_t l = j + 1; l < plane_paths.size(); ++l) {
      const auto& a = m.colliders.planes[first + j];
      const auto& b = m.colliders.planes[first + l];
      double facing = 0;  // a.normal · b.normal: −1 when they face each other (unit normals)
      for (int k = 0; k < 3; ++k) facing += a.normal[static_cast<size_t>(k)] * b.normal[static_cast<size_t>(k)];
      if (facing > -1 + 1e-12) continue;
      // Free sides n·x ≥ a.offset and −n·x ≥ b.offset: a slot from a.offset to −b.offset along n.
      const double width = -b.offset - a.offset;
      if (!(width > 0))
        throw SceneError(plane_paths[l], "its free side and " + plane_paths[j] + "'s " +
                                             (width == 0 ? std::string("meet in a plane only")
                                                         : "do not overlap (a gap of " + nlohmann::json(-width).dump() +
                                                               " m between them)") +
                                             ": no body can be on both");
      for (size_t i = 0; i < listed; ++i) {
        const double r = m.bodies[i].radius;
        if (r > 0 && 2 * r >= width)
          throw SceneError("bodies[" + std::to_string(i) + "].radius",
                           "a ball of radius " + nlohmann::json(r).dump() + " does not fit between the planes " +
                               plane_paths[j] + " and " + plane_paths[l] + " (" + nlohmann::json(width).dump() +
                               " m apart; a ball must be narrower than its slot)");
      }
    }
}

MechanicalDescription read_mechanical(JsonFields& scene, MechanicalFields& fields) {
  MechanicalDescription m;
  const long d = scene.integer("dimensions");
  if (d < 1 || d > 3) scene.fail("dimensions", "must be 1, 2 or 3 (got " + std::to_string(d) + ")");
  m.dimensions = static_cast<int>(d);
  for (auto& b : scene.objects("bodies")) {
    BodyDescription body;
    body.mass = b.positive("mass");
    body.position = b.numbers("position", m.dimensions);
    body.velocity = b.numbers("velocity", m.dimensions, std::vector<double>(static_cast<size_t>(d), 0.0));
    body.radius = b.non_negative("radius", 0);
    // Times of impact square distances: r² must be a normal double, as must (r_a + r_b)².
    if (body.radius > 0 && !(body.radius >= 1e-100 && body.radius <= 1e100))
      b.fail("radius", "must be 0 (a point) or between 1e-100 and 1e100 m (got " + nlohmann::json(body.radius).dump() + ")");
    body.restitution = restitution(b, "restitution");
    // A speed whose kinetic energy is past the largest double makes every energy measure
    // infinite from the start, and the first steps blamed the integrator.
    double speed2 = 0;
    for (double c : body.velocity) speed2 += c * c;
    if (!std::isfinite(0.5 * body.mass * speed2))
      b.fail("velocity", "is too large for this mass: the kinetic energy ½ m |v|² is past the largest double (1.8e308)");
    b.reject_unknown();
    m.bodies.push_back(body);
  }
  const size_t listed = m.bodies.size();
  // Generators append their bodies (and walls, sticks, pins) after the listed ones.
  fields.listed = listed;
  if (scene.has("lattice")) read_lattice(scene.object("lattice"), m, fields);
  if (scene.has("cloth")) read_cloth(scene.object("cloth"), m, fields);
  const size_t cloth_pins = m.pins.size();  // (the generators' pins come before the listed ones: named by these)
  if (scene.has("rope")) read_rope(scene.object("rope"), m, fields);
  const size_t generated_pins = m.pins.size();
  const size_t boxes_generated = m.colliders.boxes.size();
  if (m.bodies.empty()) scene.fail("bodies", "needs at least one body (listed, or from a generator such as \"lattice\")");
  if (static_cast<long>(m.bodies.size()) > kMaxBodies)
    scene.fail("bodies", std::to_string(m.bodies.size()) + " bodies is more than " + std::to_string(kMaxBodies) +
                             ", the limit of a scene");

  std::vector<std::string> mutual_gravity_paths;  // (for check_coincident_under_gravity)
  for (auto& f : scene.objects("forces")) {
    const size_t springs = m.forces.springs.size(), centres = m.forces.central_gravity.size();
    read_force(f, m.dimensions, m.bodies.size(), m.forces);
    if (mutual_gravity_paths.size() < m.forces.mutual_gravity.size()) mutual_gravity_paths.push_back(f.path());
    if (m.forces.springs.size() > springs) check_spring_has_a_direction(f, m.bodies, m.forces.springs.back());
    if (m.forces.central_gravity.size() > centres) check_no_body_at_the_centre(f, m, m.forces.central_gravity.back());
  }
  std::vector<std::string> box_paths, plane_paths;  // (for the checks below)
  const size_t planes_generated = m.colliders.planes.size();
  for (auto& c : scene.objects("colliders")) {
    read_collider(c, m.dimensions, m.colliders);
    if (box_paths.size() + boxes_generated < m.colliders.boxes.size()) box_paths.push_back(c.path());
    if (plane_paths.size() + planes_generated < m.colliders.planes.size()) plane_paths.push_back(c.path());
  }
  check_balls_fit_their_boxes(m, listed, box_paths);
  check_bodies_fit_between_planes(m, listed, plane_paths);
  fields.planes_generated = planes_generated;
  fields.boxes_generated = boxes_generated;
  fields.plane_paths = plane_paths;
  fields.box_paths = box_paths;
  for (auto& f : scene.objects("sticks")) {
    StickConstraint stick;
    stick.a = body_index(f, "a", m.bodies.size());
    stick.b = body_index(f, "b", m.bodies.size());
    if (stick.a == stick.b) f.fail("b", "a stick needs two different bodies");
    const double start = distance(m.bodies[static_cast<size_t>(stick.a)], m.bodies[static_cast<size_t>(stick.b)]);
    stick.length = f.has("length") ? f.positive("length") : start;
    if (!(stick.length > 0)) f.fail("length", "the two bodies start at the same point: give the stick a length");
    f.reject_unknown();
    m.sticks.push_back(stick);
  }
  for (auto& f : scene.objects("pins")) {
    PinConstraint pin;
    pin.body = body_index(f, "body", m.bodies.size());
    pin.position = padded(f.numbers("position", m.dimensions, m.bodies[static_cast<size_t>(pin.body)].position));
    // A body has one pin: two at different points cannot both hold (the projection puts it at the last).
    for (size_t other = 0; other < m.pins.size(); ++other)
      if (m.pins[other].body == pin.body && m.pins[other].position != pin.position)
        f.fail("body", "body " + std::to_string(pin.body) + " is pinned already, at another point, by " +
                           (other < cloth_pins       ? std::string("cloth.pin")
                            : other < generated_pins ? std::string("rope.pin_first")
                                                     : "pins[" + std::to_string(other - generated_pins) + "]") +
                           ": a body can be held at one point only");
    f.reject_unknown();
    m.pins.push_back(pin);
  }
  if (static_cast<long>(m.sticks.size()) > kMaxSticks)
    scene.fail("sticks", std::to_string(m.sticks.size()) + " sticks is more than " + std::to_string(kMaxSticks) +
                             ", the limit of a scene");
  check_coincident_under_gravity(m, mutual_gravity_paths);
  const long iterations = scene.integer("constraint_iterations", 10);
  if (iterations < 1 || iterations > 10000)
    scene.fail("constraint_iterations", "must be from 1 to 10000 (got " + std::to_string(iterations) + ")");
  m.constraint_iterations = static_cast<int>(iterations);
  const long substeps = scene.integer("constraint_substeps", 1);
  if (substeps < 1 || substeps > 10000)
    scene.fail("constraint_substeps", "must be from 1 to 10000 (got " + std::to_string(substeps) + ")");
  m.constraint_substeps = static_cast<int>(substeps);
  return m;
}

FirstOrderDescription read_first_order(JsonFields system) {
  FirstOrderDescription s;
  s.type = system.string("type");
  if (s.type == "equations") return read_equations_system(system);  // right-hand sides as expressions
  const SystemInfo* info = find_first_order_system(s.type);
  if (!info) {
    std::vector<std::string> known;
    for (const auto& i : first_order_systems()) known.push_back(i.type);
    known.push_back("equations");
    system.fail("type", unknown_one_of("system", s.type, known));
  }
  for (const auto& p : info->parameters) s.parameters[p.name] = p.default_value;
  if (system.has("parameters")) {
    JsonFields parameters = system.object("parameters");
    for (const auto& p : info->parameters) s.parameters[p.name] = parameters.number(p.name, p.default_value);
    parameters.reject_unknown();
  }
  s.initial = system.numbers("initial", static_cast<int>(info->variables.size()));
  s.variables = info->variables;
  system.reject_unknown();
  return s;
}

SceneDescription read_scene(const nlohmann::json& document, const std::string& stem, const NumberTexts* texts) {
  JsonFields f(document, "", texts);
  SceneDescription scene;
  MechanicalFields fields;
  f.string("$schema", "");  // editors may point at scene/scene.schema.json
  scene.name = f.string("name", stem);
  if (scene.name.empty()) scene.name = stem;  // (a blank title on every output, and folders named "compare-")
  scene.description = f.string("description", "");
  // A name is a title, drawn on every frame and every figure and printed on every row of a CSV: one
  // of 60 MB loaded, then took minutes a frame to lay out.
  if (scene.name.size() > 1000) f.fail("name", "is " + std::to_string(scene.name.size()) + " bytes long (at most 1,000: a title; the description may be longer)");
  // Both are printed on the terminal and in every report: a control character (an escape
  // sequence, C0's or C1's, a carriage return) there would rewrite the user's screen, not name a
  // scene. Line breaks and tabs may be in them: the name is made one line here (every command
  // prints it as a line's start), the description where it is printed.
  for (const auto& [key, text] : {std::pair<const char*, const std::string&>{"name", scene.name}, {"description", scene.description}})
    for (size_t i = 0; i < text.size(); ++i) {
      const unsigned char c = static_cast<unsigned char>(text[i]);
      const bool c1 = c == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
                      static_cast<unsigned char>(text[i + 1]) <= 0x9f;  // U+0080 … U+009F in UTF-8
      if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f || c1) {
        char code[16];
        std::snprintf(code, sizeof code, c1 ? "U+%04X" : "code %u", c1 ? static_cast<unsigned char>(text[i + 1]) : c);
        f.fail(key, "has a control character (" + std::string(code) + "); only line breaks and tabs may be in it");
      }
    }
  std::replace_if(scene.name.begin(), scene.name.end(), [](char c) { return c == '\n' || c == '\t'; }, ' ');

  if (f.has("system") && f.has("bodies")) f.fail("system", "a scene has either \"system\" or \"bodies\", not both");
  if (f.has("system")) {
    scene.first_order = read_first_order(f.object("system"));
  } else if (f.has("bodies") || f.has("lattice") || f.has("cloth") || f.has("rope")) {
    scene.mechanical = read_mechanical(f, fields);
  } else {
    f.fail("bodies", "missing: a scene needs \"bodies\" (point masses) or \"system\" (a first-order system)");
  }

  scene.integrator = f.string("integrator", "rk4");
  const auto id = integrator_from_name(scene.integrator);
  if (!id)
    f.fail("integrator", unknown_one_of("integrator", scene.integrator, integrator_names()));
  if (info(*id).needs_mechanical && !scene.mechanical)
    f.fail("integrator", scene.integrator + " is symplectic and needs a mechanical scene (bodies); use " + first_order_integrator_names());
  scene.dt = f.positive("dt");
  scene.duration = f.positive("duration");
  scene.start_time = f.number("start_time", 0);
  scene.rtol = f.positive("rtol", scene.rtol);
  scene.atol = f.positive("atol", scene.atol);
  scene.output_interval = f.non_negative("output_interval", 0);

  scene.exact = f.string("exact", "");
  for (auto& r : f.objects("reference")) {
    ReferenceState state;
    state.t = r.number("t");
    // One state per time: two would make the error at that time whichever one is read.
    for (size_t j = 0; j < scene.reference.size(); ++j)
      if (scene.reference[j].t == state.t)
        r.fail("t", "reference[" + std::to_string(j) + "] has this time too: one state per time");
    const int size = scene.first_order ? static_cast<int>(scene.first_order->initial.size())
                                       : 2 * scene.mechanical->dimensions * static_cast<int>(scene.mechanical->bodies.size());
    state.state = r.numbers("state", size);
    r.reject_unknown();
    scene.reference.push_back(state);
  }
  if (!scene.exact.empty() && !scene.reference.empty())
    f.fail("reference", "a scene has either an \"exact\" solution or \"reference\" states, not both");
  f.reject_unknown();
  check_exact_solution(scene);
  if (scene.mechanical) remember_fields(*scene.mechanical, std::move(fields));
  return scene;
}

// (an error echoes what the user wrote: printable_text.hpp)
std::string clip(const std::string& text, size_t limit) { return one_printable_line(text, limit); }

}  // namespace

// (The message up to 360 bytes: an unknown top-level field's list of the known ones is about 300, and
// at 240 it lost colliders, sticks and pins from its middle — the fields a user who wrote "walls"
// needed to see. The whole line stays within the command line's 400, or is shortened there.)
SceneFileError::SceneFileError(const std::string& file_, const std::string& field_, const std::string& message_)
    : std::runtime_error(clip(file_, 160) + ": " + (field_.empty() ? "" : clip(field_, 100) + ": ") + clip(message_, 360)),
      file(file_), field(field_), message(message_) {}

SceneDescription parse_scene(const std::string& text, const std::string& file, const std::vector<std::string>& overrides) {
  NumberTexts underflows;  // (numbers that read as 0 though they are not: the file's, then --set's)
  nlohmann::json document = parse_strict_json(text, file, &underflows);
  std::string current;
  try {
    for (const auto& o : overrides) {
      current = o;
      // The value is held to the file's rules too (a key once per object, the nesting), as if
      // the file had said it.
      if (const auto equals = o.find('='); equals != std::string::npos) {
        const std::string path = o.substr(0, equals);
        const auto inside = [&path](const std::string& inner) {
          return inner.empty() ? path : path + (inner[0] == '[' ? "" : ".") + inner;
        };
        // (What the file said there is gone: so are its numbers that read as 0.)
        std::erase_if(underflows, [&path](const auto& u) {
          return u.first == path || u.first.starts_with(path + ".") || u.first.starts_with(path + "[");
        });
        NumberTexts set_underflows;
        FieldPathTracker checker;
        checker.keep_underflows(&set_underflows);
        if (!nlohmann::json::sax_parse(o.substr(equals + 1), &checker) && !checker.problem().empty())
          throw SceneError(inside(checker.path()), checker.problem());
        for (const auto& [inner, written] : set_underflows) underflows[inside(inner)] = written;
      }
      apply_override(document, o);
    }
    current.clear();
    return read_scene(document, std::filesystem::path(file).stem().string(), &underflows);
  } catch (const SceneError& e) {
    std::string message = e.what();
    if (!current.empty()) message += " (in --set " + current + ")";
    throw SceneFileError(file, e.field(), message);
  }
}

SceneDescription load_scene(const std::string& file, const std::vector<std::string>& overrides) {
  // Only a regular file of a sensible size is read: not a folder, a FIFO or a device (which may
  // never end), and not a link that goes round in a circle.
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (error && error != std::errc::no_such_file_or_directory)
    throw SceneFileError(file, "", "cannot be read (" + error.message() + ")");
  if (!std::filesystem::exists(status)) throw SceneFileError(file, "", "no such file (motus list shows the scenes)");
  if (!std::filesystem::is_regular_file(status))
    throw SceneFileError(file, "", std::filesystem::is_directory(status)
                                       ? "is a folder, not a scene file"
                                       : "is not a regular file (a FIFO or a device is not read as a scene)");
  const auto size = std::filesystem::file_size(file, error);
  if (!error && size > static_cast<std::uintmax_t>(kMaxSceneBytes))
    throw SceneFileError(file, "", "is " + std::to_string(size >> 20) + " MB, more than the " +
                                       std::to_string(kMaxSceneBytes >> 20) + " MB a scene file may have");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneFileError(file, "", "cannot be read");
  // Read to its end, not to the size it reports: a file of /proc reports 0 bytes and has more, and
  // /proc/self/status read as "unexpected end of input", as if empty.
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<size_t>(in.gcount()));
    if (text.size() > static_cast<size_t>(kMaxSceneBytes))
      throw SceneFileError(file, "", "is more than the " + std::to_string(kMaxSceneBytes >> 20) + " MB a scene file may have");
  }
  if (in.bad()) throw SceneFileError(file, "", "cannot be read");
  return parse_scene(text, file, overrides);
}

}  // namespace motus
