#include "motus/scene_file/scene_file.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "motus/scene_file/json_fields.hpp"
#include "motus/ball_lattice.hpp"
#include "motus/scene_generators.hpp"
#include "motus/exact/exact_solution.hpp"
#include "motus/integrator_name.hpp"
#include "motus/scene_error.hpp"
#include "motus/systems/system_catalog.hpp"
#include "motus/scene_file/scene_overrides.hpp"

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
    if (d != 1) f.fail("type", "a pendulum force acts on a 1-D body (its angle); this scene has " + std::to_string(d) + " dimensions");
    PendulumTorque p;
    p.body = f.has("body") ? body_index(f, "body", bodies) : 0;
    p.g = f.positive("g", 9.81);
    p.length = f.positive("length");
    forces.pendulums.push_back(p);
  } else {
    f.fail("type", "unknown force \"" + type + "\" (known: gravity, spring, drag, central_gravity, mutual_gravity, pendulum)");
  }
  f.reject_unknown();
}

double restitution(JsonFields& f, const std::string& key) {
  const double e = f.number(key, 1.0);
  if (e < 0 || e > 1) f.fail(key, "must be between 0 and 1 (got " + nlohmann::json(e).dump() + ")");
  return e;
}

void read_lattice(JsonFields f, MechanicalDescription& m) {
  BallLattice lattice;
  lattice.count = f.integer("count");
  if (lattice.count < 1 || lattice.count > 10'000'000) f.fail("count", "must be from 1 to 10,000,000");
  lattice.spacing = f.positive("spacing", lattice.spacing);
  lattice.radius = f.positive("radius", lattice.radius);
  if (2 * lattice.radius > lattice.spacing) f.fail("radius", "balls of this radius overlap at this spacing");
  lattice.mass = f.positive("mass", lattice.mass);
  lattice.speed = f.non_negative("speed", lattice.speed);
  const long seed = f.integer("seed", 1);
  if (seed < 0) f.fail("seed", "must be >= 0");
  lattice.seed = static_cast<std::uint64_t>(seed);
  lattice.restitution = restitution(f, "restitution");
  lattice.origin = padded(f.numbers("origin", m.dimensions, std::vector<double>(static_cast<size_t>(m.dimensions), 0.0)));
  lattice.container = f.boolean("container", true);
  f.reject_unknown();
  add_ball_lattice(m, lattice);
}

int small_count(JsonFields& f, const std::string& key, long fallback, long max) {
  const long n = f.integer(key, fallback);
  if (n < 1 || n > max) f.fail(key, "must be from 1 to " + std::to_string(max));
  return static_cast<int>(n);
}

void read_cloth(JsonFields f, MechanicalDescription& m) {
  ClothGenerator cloth;
  cloth.rows = small_count(f, "rows", cloth.rows, 1000);
  cloth.columns = small_count(f, "columns", cloth.columns, 1000);
  cloth.spacing = f.positive("spacing", cloth.spacing);
  cloth.mass = f.positive("mass", cloth.mass);
  cloth.origin = padded(f.numbers("origin", m.dimensions, std::vector<double>(static_cast<size_t>(m.dimensions), 0.0)));
  cloth.shear = f.boolean("shear", cloth.shear);
  cloth.pin = f.string("pin", cloth.pin);
  cloth.plane = f.string("plane", cloth.plane);
  f.reject_unknown();
  add_cloth(m, cloth);  // SceneError("cloth.pin", ...) for values it cannot build
}

void read_rope(JsonFields f, MechanicalDescription& m) {
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
  add_rope(m, rope);
}

void read_collider(JsonFields& f, int d, Colliders& colliders) {
  const std::string type = f.string("type");
  if (type == "plane") {
    PlaneCollider p;
    const auto normal = f.numbers("normal", d);
    double length2 = 0;
    for (double c : normal) length2 += c * c;
    if (length2 == 0) f.fail("normal", "must not be zero");
    p.normal = padded(normal);
    p.offset = f.number("offset", 0);
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
    if (d != 2) f.fail("type", "segments exist in 2-D scenes only; this scene has " + std::to_string(d) + " dimensions");
    SegmentCollider s;
    s.a = padded(f.numbers("a", d));
    s.b = padded(f.numbers("b", d));
    if (s.a == s.b) f.fail("b", "a segment needs two different end points");
    s.restitution = restitution(f, "restitution");
    colliders.segments.push_back(s);
  } else {
    f.fail("type", "unknown collider \"" + type + "\" (known: plane, box, segment)");
  }
  f.reject_unknown();
}

double distance(const BodyDescription& a, const BodyDescription& b) {
  double s = 0;
  for (size_t k = 0; k < a.position.size(); ++k) s += (a.position[k] - b.position[k]) * (a.position[k] - b.position[k]);
  return std::sqrt(s);
}

MechanicalDescription read_mechanical(JsonFields& scene) {
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
    body.restitution = restitution(b, "restitution");
    b.reject_unknown();
    m.bodies.push_back(body);
  }
  // Generators append their bodies (and walls, sticks, pins) after the listed ones.
  if (scene.has("lattice")) read_lattice(scene.object("lattice"), m);
  if (scene.has("cloth")) read_cloth(scene.object("cloth"), m);
  if (scene.has("rope")) read_rope(scene.object("rope"), m);
  if (m.bodies.empty()) scene.fail("bodies", "needs at least one body (listed, or from a generator such as \"lattice\")");

  for (auto& f : scene.objects("forces")) read_force(f, m.dimensions, m.bodies.size(), m.forces);
  for (auto& c : scene.objects("colliders")) read_collider(c, m.dimensions, m.colliders);
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
    f.reject_unknown();
    m.pins.push_back(pin);
  }
  const long iterations = scene.integer("constraint_iterations", 10);
  if (iterations < 1 || iterations > 10000) scene.fail("constraint_iterations", "must be from 1 to 10000");
  m.constraint_iterations = static_cast<int>(iterations);
  return m;
}

FirstOrderDescription read_first_order(JsonFields system) {
  FirstOrderDescription s;
  s.type = system.string("type");
  const SystemInfo* info = find_first_order_system(s.type);
  if (!info) {
    std::string known;
    for (const auto& i : first_order_systems()) known += (known.empty() ? "" : ", ") + i.type;
    system.fail("type", "unknown system \"" + s.type + "\" (known: " + known + ")");
  }
  for (const auto& p : info->parameters) s.parameters[p.name] = p.default_value;
  if (system.has("parameters")) {
    JsonFields parameters = system.object("parameters");
    for (const auto& p : info->parameters) s.parameters[p.name] = parameters.number(p.name, p.default_value);
    parameters.reject_unknown();
  }
  s.initial = system.numbers("initial", static_cast<int>(info->variables.size()));
  system.reject_unknown();
  return s;
}

SceneDescription read_scene(const nlohmann::json& document, const std::string& stem) {
  JsonFields f(document, "");
  SceneDescription scene;
  f.string("$schema", "");  // editors may point at scene/scene.schema.json
  scene.name = f.string("name", stem);
  scene.description = f.string("description", "");

  if (f.has("system") && f.has("bodies")) f.fail("system", "a scene has either \"system\" or \"bodies\", not both");
  if (f.has("system")) {
    scene.first_order = read_first_order(f.object("system"));
  } else if (f.has("bodies") || f.has("lattice") || f.has("cloth") || f.has("rope")) {
    scene.mechanical = read_mechanical(f);
  } else {
    f.fail("bodies", "missing: a scene needs \"bodies\" (point masses) or \"system\" (a first-order system)");
  }

  scene.integrator = f.string("integrator", "rk4");
  const auto id = integrator_from_name(scene.integrator);
  if (!id) f.fail("integrator", "unknown integrator \"" + scene.integrator + "\" (known: " + integrator_names() + ")");
  if (info(*id).needs_mechanical && !scene.mechanical)
    f.fail("integrator", scene.integrator + " is symplectic and needs a mechanical scene (bodies); use euler, midpoint, rk4, rk4-doubling or rk45");
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
  return scene;
}

// Where in the document a parse failed, as a field path: a SAX pass that keeps the
// path of keys and indices and stops at the error nlohmann reports.
class FieldPathTracker : public nlohmann::json::json_sax_t {
public:
  std::string path() const {
    std::string p;
    for (const auto& frame : stack_) {
      if (frame.is_array) {
        if (frame.index >= 0) p += "[" + std::to_string(frame.index) + "]";
      } else if (!frame.key.empty()) {
        p += (p.empty() ? "" : ".") + frame.key;
      }
    }
    return p;
  }
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    advance();
    stack_.push_back({false, -1, ""});
    return true;
  }
  bool key(string_t& k) override {
    stack_.back().key = k;
    return true;
  }
  bool end_object() override { return end(); }
  bool start_array(std::size_t) override {
    advance();
    stack_.push_back({true, -1, ""});
    return true;
  }
  bool end_array() override { return end(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception&) override { return false; }

private:
  struct Frame {
    bool is_array;
    long index;
    std::string key;
  };
  void advance() {
    if (!stack_.empty() && stack_.back().is_array) ++stack_.back().index;
  }
  bool value() {
    advance();
    return true;
  }
  bool end() {
    stack_.pop_back();
    return true;
  }
  std::vector<Frame> stack_;
};

[[noreturn]] void throw_parse_error(const std::string& text, const std::string& file, const nlohmann::json::exception& e,
                                    std::size_t byte) {
  FieldPathTracker tracker;
  nlohmann::json::sax_parse(text, &tracker);
  // nlohmann reports a byte offset; people want a line and a column.
  size_t line = 1, column = 1;
  for (size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  std::string what = e.what();
  const auto bracket = what.find("] ");
  if (bracket != std::string::npos) what = what.substr(bracket + 2);
  if (const auto colon = what.find(": "); e.id == 101 && colon != std::string::npos) what = what.substr(colon + 2);
  if (e.id == 406) what += " (numbers must be finite)";
  const std::string where = byte ? " at line " + std::to_string(line) + ", column " + std::to_string(column) : "";
  throw SceneFileError(file, tracker.path(), "malformed JSON" + where + ": " + what);
}

}  // namespace

SceneFileError::SceneFileError(const std::string& file_, const std::string& field_, const std::string& message_)
    : std::runtime_error(file_ + ": " + (field_.empty() ? "" : field_ + ": ") + message_),
      file(file_), field(field_), message(message_) {}

SceneDescription parse_scene(const std::string& text, const std::string& file, const std::vector<std::string>& overrides) {
  nlohmann::json document;
  try {
    document = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw_parse_error(text, file, e, e.byte);
  } catch (const nlohmann::json::exception& e) {  // e.g. 1e999: number overflow
    throw_parse_error(text, file, e, 0);
  }
  std::string current;
  try {
    for (const auto& o : overrides) {
      current = o;
      apply_override(document, o);
    }
    current.clear();
    return read_scene(document, std::filesystem::path(file).stem().string());
  } catch (const SceneError& e) {
    std::string message = e.what();
    if (!current.empty()) message += " (in --set " + current + ")";
    throw SceneFileError(file, e.field(), message);
  }
}

SceneDescription load_scene(const std::string& file, const std::vector<std::string>& overrides) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    const bool exists = std::filesystem::exists(file);
    throw SceneFileError(file, "", exists ? "cannot be read" : "no such file (motus list shows the scenes)");
  }
  std::stringstream text;
  text << in.rdbuf();
  return parse_scene(text.str(), file, overrides);
}

}  // namespace motus
