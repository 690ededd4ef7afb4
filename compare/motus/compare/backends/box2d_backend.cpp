#include "motus/compare/backends/box2d_backend.hpp"

#include <box2d/box2d.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <new>
#include <optional>
#include <string>

#include "motus/compare/backends/note_format.hpp"
#include "motus/compare/backends/peer_forces.hpp"
#include "motus/compare/backends/starting_outside.hpp"
#include "motus/compare/metrics.hpp"

// Box2D does not check its allocations either (b2BlockAllocator writes into the chunk b2Alloc gave
// it): with malloc refusing (a memory limit, `ulimit -v`) it would write through a null pointer.
// Debian's libbox2d calls b2Alloc_Default through its PLT, so this definition — exported, as
// b2_settings.h declares it — takes its place (in the motus-peers.so that links this file, and in
// a program linking it), and throws std::bad_alloc where malloc returns nothing: the run then ends
// as any other that ran out of memory. (b2Free_Default is Box2D's own: free.)
__attribute__((visibility("default"))) void* b2Alloc_Default(int32 size) {
  if (void* p = std::malloc(size > 0 ? static_cast<size_t>(size) : 1)) return p;
  throw std::bad_alloc();
}

namespace motus::compare {
namespace {

// docs/peers.md: the manual's recommended iterations.
constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;
// A point (radius 0) is a circle this small: Box2D needs a shape for a contact with a
// wall; with the edges' skin of b2_polygonRadius its continuous collision still works.
constexpr double kPointRadius = 1e-4;  // m
// A plane is an edge this much longer on each side than the bodies' spread along it, about
// their centroid (the room they have to move along it).
constexpr double kPlaneHalfLength = 1e4;  // m
// Collision filter: balls meet walls and balls, points meet walls only (as in motus).
constexpr std::uint16_t kWallBits = 0x1, kBallBits = 0x2, kPointBits = 0x4;

// Each fixture's e (a double owned by the world) hangs from its user data.
double restitution_of(b2Fixture* fixture) {
  return *reinterpret_cast<const double*>(fixture->GetUserData().pointer);
}

// motus mixes a contact's restitution as the product eA·eB (collide/impulse.hpp);
// Box2D's default is max(eA, eB). PreSolve runs for every touching contact before the
// solver reads the contact's restitution, in the discrete step and in the TOI sub-steps.
class ProductRestitution final : public b2ContactListener {
public:
  void PreSolve(b2Contact* contact, const b2Manifold* /*old_manifold*/) override {
    contact->SetRestitution(
        static_cast<float>(restitution_of(contact->GetFixtureA()) * restitution_of(contact->GetFixtureB())));
  }
};

// A 1-D scene is the x axis of Box2D's plane: every body at y = 0, every wall a vertical edge (a
// 1-D box is its two ends; its other faces are a plane's half length away). Nothing can push a
// body off the axis: the scene's forces act along x, and a contact between two centres on it, or
// with a wall across it, has its normal along x, so y stays exactly 0.
MechanicalDescription on_the_x_axis(const MechanicalDescription& line) {
  MechanicalDescription plane = line;
  plane.dimensions = 2;
  for (auto& b : plane.bodies) {
    b.position.resize(2, 0.0);
    b.velocity.resize(2, 0.0);
  }
  for (auto& box : plane.colliders.boxes) {
    box.min[1] = -kPlaneHalfLength;
    box.max[1] = kPlaneHalfLength;
  }
  return plane;  // (planes' and pins' further coordinates are already 0: the loader pads them)
}

}  // namespace

struct Box2dBackend::World {
  ProductRestitution listener;         // outlives `world`, which points to it
  std::deque<double> restitution;      // every fixture's e (stable addresses)
  std::unique_ptr<b2World> world;
  std::vector<b2Body*> bodies;         // in the scene's order
  std::vector<double> inverse_mass;    // 0 for pinned (static) bodies
  std::vector<double> bullet_reach;    // a free ball's radius (0: never a bullet): see step()
  std::unique_ptr<PeerForces> forces;  // null when the scene has no force but uniform gravity
  double gravity[2] = {0, 0};
  double dt = 0, t0 = 0;
  long steps = 0;
  size_t d = 2;                 // the scene's dimensions: 2, or 1 on the x axis (on_the_x_axis)
  const char* unit = "m";       // of the coordinates: "rad" where the one coordinate is a pendulum's angle
  std::vector<double> x, v, F;  // scratch: the state in double (d numbers a body), the forces

  // What the settings and notes report.
  bool has_forces = false, has_sticks = false, has_pins = false, has_contacts = false, has_points = false,
       has_segments = false;
  double start_fastest = 0;  // the fastest body's speed·dt at the start, m
  double farthest = 0;       // the largest |x| of a body, at the start and after every watched step, m
  double run_fastest = 0;    // the largest speed·dt before (after the kick) or after any watched step, m
  long capped = 0;           // body-steps that b2_maxTranslation slowed: see step()
  long bullet_steps = 0;     // body-steps taken as a bullet (moving more than its radius)
  long first_capped_step = -1;
  struct Stick {
    size_t a, b;
    double length;
  };
  std::vector<Stick> sticks;
  std::vector<unsigned char> over_cap;  // scratch: whether a body began the step faster than the cap
  double worst_stick = 0;  // the largest |length − rest| / rest after any step
  long worst_stick_step = 0;

  // Every body's position and velocity, d numbers each, in double.
  void read_state(std::vector<double>& to_x, std::vector<double>& to_v) const {
    const size_t n = bodies.size();
    to_x.resize(d * n);
    to_v.resize(d * n);
    for (size_t i = 0; i < n; ++i) {
      const b2Vec2& p = bodies[i]->GetPosition();
      const b2Vec2& u = bodies[i]->GetLinearVelocity();
      to_x[d * i] = p.x;
      to_v[d * i] = u.x;
      if (d == 2) {
        to_x[d * i + 1] = p.y;
        to_v[d * i + 1] = u.y;
      }
    }
  }
  // Body i's force from F (the y part 0 in a 1-D scene).
  b2Vec2 force_on(size_t i) const {
    return {static_cast<float>(F[d * i]), d == 2 ? static_cast<float>(F[d * i + 1]) : 0.0f};
  }

  b2Fixture* add_fixture(b2Body* body, const b2Shape& shape, double e, std::uint16_t category, std::uint16_t mask) {
    b2FixtureDef def;
    def.shape = &shape;
    def.density = 0;  // the mass is set exactly with SetMassData
    def.friction = 0;  // motus has no friction
    def.restitution = static_cast<float>(e);
    def.restitutionThreshold = 0;  // docs/peers.md: the default 1 m/s gives slower contacts no bounce
    def.filter.categoryBits = category;
    def.filter.maskBits = mask;
    def.userData.pointer = reinterpret_cast<std::uintptr_t>(&restitution.emplace_back(e));
    return body->CreateFixture(&def);
  }

  b2Body* add_static_body(double px, double py) {
    b2BodyDef def;
    def.type = b2_staticBody;
    def.position.Set(static_cast<float>(px), static_cast<float>(py));
    return world->CreateBody(&def);
  }

  void add_edge(b2Body* body, double ax, double ay, double bx, double by, double e) {
    b2EdgeShape edge;  // two-sided; its m_radius is b2_polygonRadius
    edge.SetTwoSided(b2Vec2(static_cast<float>(ax), static_cast<float>(ay)),
                     b2Vec2(static_cast<float>(bx), static_cast<float>(by)));
    add_fixture(body, edge, e, kWallBits, kBallBits | kPointBits);
  }
};

Box2dBackend::Box2dBackend() = default;
Box2dBackend::~Box2dBackend() = default;

// Not from b2_version: Box2D 2.4.1's library still says 2.4.0 there (upstream never
// bumped it; Debian's libbox2d.so.2.4.1 and box2dConfigVersion.cmake say 2.4.1).
std::string Box2dBackend::version() const { return "Box2D 2.4.1, float"; }

void Box2dBackend::build(const SceneDescription& scene, const Method& /*method*/, double dt) {
  world_.reset();
  if (!scene.mechanical) throw Unsupported("box2d", {"first-order systems (box2d runs point masses)"});
  const MechanicalDescription& as_written = *scene.mechanical;
  if (as_written.dimensions != 1 && as_written.dimensions != 2)
    throw Unsupported("box2d", {std::to_string(as_written.dimensions) + "-D scenes"});
  std::optional<MechanicalDescription> on_axis;
  if (as_written.dimensions == 1) on_axis = on_the_x_axis(as_written);
  const MechanicalDescription& m = on_axis ? *on_axis : as_written;

  const size_t n = m.bodies.size();
  std::vector<const PinConstraint*> pin_of(n, nullptr);
  for (const auto& p : m.pins) pin_of[static_cast<size_t>(p.body)] = &p;  // the last pin of a body wins, as in motus
  auto start_position = [&](size_t i, int k) {
    return pin_of[i] ? pin_of[i]->position[static_cast<size_t>(k)] : m.bodies[i].position[static_cast<size_t>(k)];
  };

  // What Box2D cannot express faithfully: refuse rather than run another scene.
  std::vector<std::string> unsupported;
  // Box2D is float, and squares lengths: past 1e18 a square overflows float's range (3.4e38), and
  // Box2D's own assertions (b2Body: position.IsValid(); b2CollideEdgeAndCircle: den > 0) would
  // end the whole comparison.
  constexpr double kFloatReach = 1e18;
  auto beyond = [&](std::initializer_list<double> numbers) {
    return std::any_of(numbers.begin(), numbers.end(), [&](double x) { return !(std::abs(x) <= kFloatReach); });
  };
  for (size_t i = 0; i < n; ++i) {
    const auto& b = m.bodies[i];
    if (beyond({b.mass, b.radius, start_position(i, 0), start_position(i, 1), b.velocity[0], b.velocity[1]})) {
      unsupported.push_back(format("body %zu: a mass, size, position or speed past 1e18 (float squares past its range)", i));
      break;
    }
  }
  for (size_t j = 0; j < m.colliders.planes.size(); ++j)
    if (beyond({m.colliders.planes[j].offset}))
      unsupported.push_back(format("plane %zu: an offset past 1e18 (float squares past its range)", j));
  for (size_t j = 0; j < m.colliders.boxes.size(); ++j) {
    const auto& b = m.colliders.boxes[j];
    if (beyond({b.min[0], b.min[1], b.max[0], b.max[1], b.max[0] - b.min[0], b.max[1] - b.min[1]}))
      unsupported.push_back(format("box %zu: a corner past 1e18 (float squares past its range)", j));
  }
  for (size_t j = 0; j < m.colliders.segments.size(); ++j) {
    const auto& s = m.colliders.segments[j];
    if (beyond({s.a[0], s.a[1], s.b[0], s.b[1], s.b[0] - s.a[0], s.b[1] - s.a[1]}))
      unsupported.push_back(format("segment %zu: an end past 1e18 (float squares past its range)", j));
  }
  for (const auto& away : bodies_pinned_away(m))
    unsupported.push_back(away + " (motus moves it to the pin at the first step; Box2D makes it there)");
  for (const auto& outside : bodies_starting_outside(m))
    unsupported.push_back(outside + " (motus moves it onto the wall's side; Box2D's edges would keep it on the other)");
  for (size_t i = 0; i < n; ++i)
    if (!pin_of[i] && !(static_cast<float>(m.bodies[i].mass) >= FLT_MIN)) {
      unsupported.push_back(format("body %zu: a mass of %g kg, below float's smallest normal number (Box2D would make "
                                   "it 1 kg)",
                                   i, m.bodies[i].mass));
      break;
    }
  for (size_t j = 0; j < m.sticks.size(); ++j)
    if (m.sticks[j].length < b2_linearSlop)
      unsupported.push_back(format("stick %zu of length %g m (b2DistanceJoint clamps lengths to at least "
                                   "b2_linearSlop = %g m)",
                                   j, m.sticks[j].length, static_cast<double>(b2_linearSlop)));
  if (!unsupported.empty()) throw Unsupported("box2d", unsupported);

  auto w = std::make_unique<World>();
  w->dt = dt;
  w->t0 = scene.start_time;
  w->d = static_cast<size_t>(as_written.dimensions);
  if (!as_written.forces.pendulums.empty()) w->unit = "rad";  // (Box2D's x is then θ: its notes say rad)
  auto forces = std::make_unique<PeerForces>(as_written);  // (in the scene's own dimensions)
  w->gravity[0] = forces->gravity()[0];
  w->gravity[1] = forces->gravity()[1];
  if (!forces->empty()) {
    w->forces = std::move(forces);
    w->has_forces = true;
  }
  w->world = std::make_unique<b2World>(b2Vec2(static_cast<float>(w->gravity[0]), static_cast<float>(w->gravity[1])));
  w->world->SetAllowSleeping(false);
  w->world->SetContactListener(&w->listener);
  // Box2D's defaults, stated: warm starting and continuous physics on, sub-stepping off.
  w->world->SetWarmStarting(true);
  w->world->SetContinuousPhysics(true);
  w->world->SetSubStepping(false);

  // Bodies, in the scene's order.
  int balls = 0;
  double cx = 0, cy = 0;  // the bodies' centroid, where planes are centred
  for (size_t i = 0; i < n; ++i) {
    const BodyDescription& body = m.bodies[i];
    const bool pinned = pin_of[i] != nullptr, ball = body.radius > 0;
    b2BodyDef def;
    def.type = pinned ? b2_staticBody : b2_dynamicBody;
    def.position.Set(static_cast<float>(start_position(i, 0)), static_cast<float>(start_position(i, 1)));
    if (!pinned) def.linearVelocity.Set(static_cast<float>(body.velocity[0]), static_cast<float>(body.velocity[1]));
    def.fixedRotation = true;  // frictionless balls never spin
    def.bullet = false;  // (set step by step: see step())
    def.allowSleep = false;
    def.awake = true;
    def.linearDamping = 0;
    def.angularDamping = 0;
    b2Body* b = w->world->CreateBody(&def);

    b2CircleShape circle;
    circle.m_radius = static_cast<float>(ball ? body.radius : kPointRadius);
    if (ball)
      w->add_fixture(b, circle, body.restitution, kBallBits, kWallBits | kBallBits);
    else
      w->add_fixture(b, circle, body.restitution, kPointBits, kWallBits);
    if (!pinned) {
      b2MassData mass;
      mass.mass = static_cast<float>(body.mass);
      mass.center.SetZero();
      mass.I = 0;  // fixed rotation: no inertia
      b->SetMassData(&mass);
    }
    w->bodies.push_back(b);
    w->inverse_mass.push_back(pinned ? 0.0 : 1 / body.mass);
    w->bullet_reach.push_back(ball && !pinned ? body.radius : 0.0);
    balls += ball ? 1 : 0;
    w->has_points = w->has_points || !ball;
    w->has_pins = w->has_pins || pinned;
    cx += start_position(i, 0) / static_cast<double>(n);
    cy += start_position(i, 1) / static_cast<double>(n);
    w->farthest = std::max(w->farthest, std::hypot(start_position(i, 0), start_position(i, 1)));
    if (!pinned) w->start_fastest = std::max(w->start_fastest, std::hypot(body.velocity[0], body.velocity[1]) * dt);
  }

  // Walls. Box2D's edges have a skin of b2_polygonRadius: planes and box faces are moved
  // back by it, into the wall, so that their surface is where the scene puts it.
  const double skin = b2_polygonRadius;
  for (const auto& p : m.colliders.planes) {
    const double length = std::hypot(p.normal[0], p.normal[1]);
    const double nx = p.normal[0] / length, ny = p.normal[1] / length, offset = p.offset / length - skin;
    // The edge's centre: the centroid projected onto the edge's line; its ends symmetric
    // about it, so that float rounding keeps the line through that centre.
    const double s = nx * cx + ny * cy - offset;
    b2Body* wall = w->add_static_body(cx - s * nx, cy - s * ny);
    // (Bodies 3·10⁴ m apart along the floor were past a fixed 10⁴ m's ends, and fell through.)
    double spread = 0;
    for (size_t i = 0; i < n; ++i)
      spread = std::max(spread, std::abs(-ny * (start_position(i, 0) - cx) + nx * (start_position(i, 1) - cy)));
    const double half = spread + kPlaneHalfLength;
    const double tx = -ny * half, ty = nx * half;
    w->add_edge(wall, -tx, -ty, tx, ty, p.restitution);
  }
  for (const auto& box : m.colliders.boxes) {
    const double mx = (box.min[0] + box.max[0]) / 2, my = (box.min[1] + box.max[1]) / 2;
    const double hx = (box.max[0] - box.min[0]) / 2 + skin, hy = (box.max[1] - box.min[1]) / 2 + skin;
    b2Body* wall = w->add_static_body(mx, my);
    w->add_edge(wall, -hx, -hy, hx, -hy, box.restitution);
    w->add_edge(wall, hx, -hy, hx, hy, box.restitution);
    w->add_edge(wall, hx, hy, -hx, hy, box.restitution);
    w->add_edge(wall, -hx, hy, -hx, -hy, box.restitution);
  }
  for (const auto& seg : m.colliders.segments) {
    // Two-sided: the skin cannot be moved back, so a segment is 2·b2_polygonRadius thick.
    const double mx = (seg.a[0] + seg.b[0]) / 2, my = (seg.a[1] + seg.b[1]) / 2;
    b2Body* wall = w->add_static_body(mx, my);
    w->add_edge(wall, seg.a[0] - mx, seg.a[1] - my, seg.b[0] - mx, seg.b[1] - my, seg.restitution);
  }
  w->has_segments = !m.colliders.segments.empty();
  w->has_contacts = !m.colliders.empty() || balls >= 2;

  // Sticks: rigid distance joints (2.4.1: minLength == maxLength is the rigid constraint,
  // stiffness 0 no spring). Joined balls still collide, as they do in motus.
  for (const auto& stick : m.sticks) {
    b2DistanceJointDef def;
    def.bodyA = w->bodies[static_cast<size_t>(stick.a)];
    def.bodyB = w->bodies[static_cast<size_t>(stick.b)];
    def.localAnchorA.SetZero();
    def.localAnchorB.SetZero();
    def.length = def.minLength = def.maxLength = static_cast<float>(stick.length);
    def.stiffness = 0;
    def.damping = 0;
    def.collideConnected = true;
    w->world->CreateJoint(&def);
    w->sticks.push_back({static_cast<size_t>(stick.a), static_cast<size_t>(stick.b), stick.length});
  }
  w->has_sticks = !m.sticks.empty();
  world_ = std::move(w);
}

void Box2dBackend::step() {
  World& w = *world_;
  const double t = w.t0 + static_cast<double>(w.steps) * w.dt;
  if (w.forces) {
    // The scene's forces at the step's start, by motus's formulas: Box2D's kick is then
    // v += dt·(g + F/m), symplectic Euler's.
    w.read_state(w.x, w.v);
    w.forces->compute(t, w.x, w.v, w.F);
    for (size_t i = 0; i < w.bodies.size(); ++i)
      if (w.inverse_mass[i] > 0)
        w.bodies[i]->ApplyForceToCenter(w.force_on(i), true);
  }
  // A ball is a bullet (continuous collision against the other moving balls too, not only walls)
  // for a step in which it moves more than its radius — where discrete detection could let two
  // balls pass through each other — as Bullet arms its CCD (a motion threshold of the radius).
  // Not always: a bullet's every touching pair gets a time-of-impact sub-step, which costs time
  // and, in ball_gas, where no ball moves a tenth of its radius in a step (the fastest, 2.4 m/s at
  // 1/60 s, 0.08 of it), put +4.8e-3 into
  // the kinetic energy in one step (400 balls; 0 to 2e-7 without).
  for (size_t i = 0; i < w.bodies.size(); ++i) {
    if (w.bullet_reach[i] == 0) continue;
    const b2Vec2& u = w.bodies[i]->GetLinearVelocity();
    const b2Vec2 force = w.forces ? w.force_on(i) : b2Vec2(0, 0);
    const double kick[2] = {w.gravity[0] + force.x * w.inverse_mass[i], w.gravity[1] + force.y * w.inverse_mass[i]};
    const bool fast = std::hypot(u.x + w.dt * kick[0], u.y + w.dt * kick[1]) * w.dt > w.bullet_reach[i];
    w.bodies[i]->SetBullet(fast);
    w.bullet_steps += fast && watching_ ? 1 : 0;
  }
  // b2_maxTranslation: Box2D scales down a velocity that would carry a body farther than
  // 2 m in the step, so a capped body ends the step at exactly that speed — unless a contact
  // then changes it within the step (continuous collision: a ball at 1e5 m/s in a box hits a
  // wall in every step, and ended none at the cap, so none was counted and the note said "not
  // reached" of a run the cap had slowed from its first step). So a body-step counts as capped
  // also when the body began it (after the forces' kick) faster than the cap.
  const double cap = b2_maxTranslation;
  if (watching_) {
    w.over_cap.assign(w.bodies.size(), 0);
    for (size_t i = 0; i < w.bodies.size(); ++i) {
      if (w.inverse_mass[i] == 0) continue;
      const b2Vec2& u = w.bodies[i]->GetLinearVelocity();
      const b2Vec2 force = w.forces ? w.force_on(i) : b2Vec2(0, 0);
      const double kick[2] = {w.gravity[0] + force.x * w.inverse_mass[i], w.gravity[1] + force.y * w.inverse_mass[i]};
      const double travel = std::hypot(u.x + w.dt * kick[0], u.y + w.dt * kick[1]) * w.dt;
      w.run_fastest = std::max(w.run_fastest, travel);
      w.over_cap[i] = travel > cap ? 1 : 0;
    }
  }
  w.world->Step(static_cast<float>(w.dt), kVelocityIterations, kPositionIterations);
  ++w.steps;
  if (!watching_) return;

  for (size_t i = 0; i < w.bodies.size(); ++i) {
    if (w.inverse_mass[i] == 0) continue;
    const b2Vec2& u = w.bodies[i]->GetLinearVelocity();
    const b2Vec2& p = w.bodies[i]->GetPosition();
    w.farthest = std::max(w.farthest, std::hypot(static_cast<double>(p.x), static_cast<double>(p.y)));
    const double travel = std::hypot(static_cast<double>(u.x), static_cast<double>(u.y)) * w.dt;
    w.run_fastest = std::max(w.run_fastest, travel);
    if (w.over_cap[i] || travel >= cap * (1 - 1e-5)) {
      ++w.capped;
      if (w.first_capped_step < 0) w.first_capped_step = w.steps;
    }
  }
  // The sticks' length error, which Box2D's iterative solver leaves.
  for (const auto& stick : w.sticks) {
    // (The difference in double, as the table's column takes it from the positions: Box2D's own float
    // subtraction rounds at 6e-8 of the coordinates, and the note read 1.26e-7 beside the column's 1.1e-7.)
    const b2Vec2& a = w.bodies[stick.a]->GetPosition();
    const b2Vec2& b = w.bodies[stick.b]->GetPosition();
    const double dx = static_cast<double>(a.x) - static_cast<double>(b.x);
    const double dy = static_cast<double>(a.y) - static_cast<double>(b.y);
    const double error = std::abs(std::sqrt(dx * dx + dy * dy) - stick.length) / stick.length;
    // (worse: a length that is not a number is the worst of all, as in the table's column; with
    // `error > worst` a run that blew up read "0% … after step 0" beside the column's inf.)
    if (const double worst = worse(w.worst_stick, error); worst != w.worst_stick) {
      w.worst_stick = worst;
      w.worst_stick_step = w.steps;
    }
  }
}

void Box2dBackend::read(Snapshot& out) const {
  const World& w = *world_;
  out.t = w.t0 + static_cast<double>(w.steps) * w.dt;
  w.read_state(out.x, out.v);
}

std::vector<std::string> Box2dBackend::settings() const {
  std::vector<std::string> s = {
      format("step: world.Step(dt, %d, %d): %d velocity and %d position iterations", kVelocityIterations,
             kPositionIterations, kVelocityIterations, kPositionIterations),
      "restitution: the product eA*eB (a PreSolve listener; Box2D's own mixing is max(eA, eB))",
      "restitution threshold: 0 m/s on every fixture",
      "friction: 0",
      "sleep: off (allowSleep = false)",
      "linear and angular damping: 0",
      "rotation: fixed (frictionless balls)",
      "continuous collision: on; a ball is a bullet in a step where it moves more than its radius (as Bullet's "
      "CCD threshold); sub-stepping off; warm starting on",
      "mass: SetMassData with each body's mass exactly",
  };
  if (!world_) return s;
  const World& w = *world_;
  s.push_back(format("gravity: world gravity (%g, %g) m/s^2", w.gravity[0], w.gravity[1]));
  if (w.has_forces) s.push_back("other forces: motus's formulas, applied with ApplyForceToCenter before every step");
  if (w.has_points) s.push_back(format("points (radius 0): circles of radius %g m that meet walls only", kPointRadius));
  if (w.has_sticks) s.push_back("sticks: b2DistanceJoint, length = minLength = maxLength, stiffness 0 (rigid)");
  if (w.has_pins) s.push_back("pins: the pinned body is a static body at the pin's position");
  if (w.d == 1)
    s.push_back("1-D: the x axis of Box2D's plane (y = 0; forces along x; a 1-D box is two vertical edges at its "
                "ends)");
  return s;
}

std::vector<std::string> Box2dBackend::notes() const {
  std::vector<std::string> s;
  if (!world_) return s;
  const World& w = *world_;
  const char* u = w.unit;
  s.push_back(format("Box2D is float: positions to ~1e-7 relative (about %.1g %s at %.3g %s from the origin, the "
                     "farthest a body came), velocities likewise",
                     std::max(w.farthest, 1.0) * 1.2e-7, u, w.farthest, u));
  const double cap = b2_maxTranslation;
  // (One line when the run never came near the cap: the start's speed and the run's said together.)
  if (w.capped == 0 && w.steps > 0) {
    const double fastest = std::max(w.run_fastest, w.start_fastest);
    s.push_back(format("b2_maxTranslation not reached in %ld steps (%g %s per step; the fastest body moved %.3g %s in a "
                       "step, %.3g%% of it, and %.3g %s at the start)",
                       w.steps, cap, u, fastest, u, 100 * fastest / cap, w.start_fastest, u));
  } else {
    s.push_back(format("b2_maxTranslation (%g %s per step): the fastest body moves %.3g %s per step at the start "
                       "(%.3g%% of it%s)",
                       cap, u, w.start_fastest, u, 100 * w.start_fastest / cap,
                       w.start_fastest > cap ? ": Box2D will slow it to the cap" : ""));
  }
  if (w.capped > 0)
    s.push_back(format("b2_maxTranslation capped %ld body-steps (first at step %ld, t = %.6g s): those bodies moved "
                       "only %g %s in a step where the scene says farther",
                       w.capped, w.first_capped_step, w.t0 + static_cast<double>(w.first_capped_step) * w.dt, cap, u));
  s.push_back("b2_maxRotation (0.5*pi per step) cannot bite: every body has fixed rotation");
  if (w.bullet_steps > 0)
    s.push_back(format("bullets: %ld body-steps of a ball moving more than its radius were taken with continuous "
                       "collision against the other balls (time-of-impact sub-steps)",
                       w.bullet_steps));
  if (w.has_contacts)
    s.push_back(format("contacts: Box2D finds them at the start of each step (continuous collision within it), lets "
                       "bodies overlap by up to b2_linearSlop = %g m and pushes overlaps apart with Baumgarte "
                       "position correction (b2_baumgarte = %g)",
                       static_cast<double>(b2_linearSlop), static_cast<double>(b2_baumgarte)));
  if (w.has_segments)
    s.push_back(format("segments keep Box2D's edge skin b2_polygonRadius = %g m: a ball's centre stays r + %g m "
                       "from them (planes and box faces are moved back by the skin)",
                       static_cast<double>(b2_polygonRadius), static_cast<double>(b2_polygonRadius)));
  if (w.has_sticks) {
    s.push_back(format("sticks are b2DistanceJoints solved by sequential impulses (%d velocity, %d position iterations), "
                       "not projected as in motus: their lengths err as far as that solver leaves them",
                       kVelocityIterations, kPositionIterations));
    if (w.steps > 0)
      s.push_back(format("sticks: the worst length error so far is %.3g%% of the rest length (after step %ld; "
                         "every step, as the table's constraint column; metrics.csv has its samples only)",
                         100 * w.worst_stick, w.worst_stick_step));
  }
  return s;
}

}  // namespace motus::compare
