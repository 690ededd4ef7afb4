#include "motus/compare/backends/bullet_backend.hpp"

#include <btBulletDynamicsCommon.h>
#include <LinearMath/btAlignedAllocator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <new>
#include <optional>
#include <string>
#include <utility>

#include "motus/compare/backends/note_format.hpp"
#include "motus/compare/backends/peer_forces.hpp"
#include "motus/compare/backends/starting_outside.hpp"
#include "motus/compare/metrics.hpp"

namespace motus::compare {
namespace {

// Collision filter groups (bits above Bullet's predefined ones): balls meet balls and
// walls; point masses meet only walls, as in motus; walls (StaticFilter) meet both.
constexpr int kBallGroup = 1 << 6;
constexpr int kPointGroup = 1 << 7;
constexpr int kWallGroup = btBroadphaseProxy::StaticFilter;

// A point mass (radius 0) needs some shape to meet walls: a sphere this small. It meets a
// wall this much before its centre would (motus lets the centre touch the wall).
constexpr double kPointRadius = 1e-3;  // m

// The solver settings this backend changes from Bullet's defaults (see settings()).
// motus has no restitution threshold (every approaching contact bounces with e), like
// Box2D's restitutionThreshold = 0 in the fair settings of docs/peers.md.
constexpr double kRestitutionVelocityThreshold = 0;  // m/s; Bullet's default 0.2

// A stick: one bilateral constraint row on the distance between the two centres,
//   C = |x_b − x_a| − L,   J = (−n, 0, n, 0) with n = (x_b − x_a)/|x_b − x_a|,
// solved by Bullet's own sequential-impulse solver with its joint ERP (Baumgarte:
// J·v = erp·(L − |d|)/dt), exactly as it solves btPoint2PointConstraint's three rows.
// Why not a stock constraint: a btPoint2PointConstraint with both pivots at the centres
// welds the two centres together; with the pivot at A's centre and B's pivot at the
// offset, B has to rotate to let the stick turn, which gives B rotational inertia (and
// energy) that a motus particle does not have, makes the angle between two sticks
// meeting at B rigid, and meets Bullet's π/4-per-step rotation clamp; btSliderConstraint
// and btGeneric6DofSpring2Constraint fix an axis in the bodies' frames, so the stick
// could turn only if the bodies rotated. This row keeps only the distance, lets the
// stick turn freely, and needs no body to rotate (angular factor 0 everywhere), so a
// cloth with more sticks than bodies works too.
class DistanceConstraint final : public btTypedConstraint {
public:
  DistanceConstraint(btRigidBody& a, btRigidBody& b, btScalar length)
      : btTypedConstraint(MAX_CONSTRAINT_TYPE, a, b), length_(length) {}

  void getInfo1(btConstraintInfo1* info) override {
    info->m_numConstraintRows = 1;
    info->nub = 0;
  }

  void getInfo2(btConstraintInfo2* info) override {
    const btVector3 d = m_rbB.getCenterOfMassPosition() - m_rbA.getCenterOfMassPosition();
    const btScalar len = d.length();
    const btVector3 n = len > 0 ? d / len : btVector3(1, 0, 0);
    for (int k = 0; k < 3; ++k) {
      info->m_J1linearAxis[k] = -n[k];
      info->m_J2linearAxis[k] = n[k];
    }
    // Angular parts stay 0 (the rows are zeroed on entry): the row acts at the centres.
    info->m_constraintError[0] = info->fps * info->erp * (length_ - len);
    // Bilateral: m_lowerLimit/m_upperLimit are ∓infinity on entry.
  }

  void setParam(int, btScalar, int) override {}
  btScalar getParam(int, int) const override { return 0; }

private:
  btScalar length_;
};

// Bullet does not check its allocations: with malloc refusing (a memory limit, `ulimit -v`) it wrote
// through the null pointer (memset in btCollisionDispatcher::getNewManifold) and motus died of
// SIGSEGV, leaving its partial report. Every Bullet allocation goes through btAlignedAllocSetCustom's
// function (its aligned allocator too, by default, adds its padding to a call of it), which here throws
// std::bad_alloc where malloc returns nothing: the run then ends as any other that ran out of memory.
void* allocate_or_throw(size_t size) {
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}

void release(void* p) { std::free(p); }

void use_allocator_that_throws() {
  static std::once_flag once;
  std::call_once(once, [] { btAlignedAllocSetCustom(allocate_or_throw, release); });
}

double norm3(const std::array<double, 3>& a, int d) {
  double s = 0;
  for (int k = 0; k < d; ++k) s += a[k] * a[k];
  return std::sqrt(s);
}

}  // namespace

struct BulletBackend::World {
  // Declaration order is destruction order reversed: the dynamics world goes first
  // (its destructor still talks to the broadphase, dispatcher and bodies).
  std::unique_ptr<btDefaultCollisionConfiguration> config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<btSequentialImpulseConstraintSolver> solver;
  std::map<double, std::unique_ptr<btSphereShape>> spheres;  // one per radius
  std::vector<std::unique_ptr<btCollisionShape>> wall_shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;  // the scene's order
  std::vector<std::unique_ptr<btRigidBody>> walls;
  std::vector<std::unique_ptr<btTypedConstraint>> sticks;
  std::unique_ptr<btDiscreteDynamicsWorld> world;

  int d = 2;
  double dt = 0;
  double t0 = 0;
  long steps = 0;
  std::optional<PeerForces> forces;
  std::vector<double> mass;
  std::vector<bool> pinned;
  std::vector<double> x, v, F;  // scratch for the forces, scene dimensions

  // What the run has met so far (for notes()).
  bool has_points_and_walls = false;
  bool has_contacts = false;
  long ccd_steps = 0;             // body-steps that moved more than the CCD threshold
  double worst_stick_error = 0;   // max |length − L|/L seen after a step
  long worst_stick_step = 0;      // the step after which it was seen
  // The widest gap at which a moving body's contact with a wall is found (the manifold's contact
  // breaking threshold; see build()), and that body's sphere radius; 0 without walls.
  double contact_threshold = 0, contact_threshold_radius = 0;
  std::vector<std::pair<size_t, size_t>> stick_bodies;
  std::vector<double> stick_lengths;

  ~World() {
    if (!world) return;
    for (auto& c : sticks) world->removeConstraint(c.get());
    for (auto& b : bodies) world->removeRigidBody(b.get());
    for (auto& w : walls) world->removeRigidBody(w.get());
    world.reset();
  }

  btVector3 to_bt(const std::vector<double>& p) const {
    btVector3 r(0, 0, 0);
    for (int k = 0; k < d && k < static_cast<int>(p.size()); ++k) r[k] = p[static_cast<size_t>(k)];
    return r;
  }

  btSphereShape* sphere(double radius) {
    auto& s = spheres[radius];
    if (!s) s = std::make_unique<btSphereShape>(radius);
    return s.get();
  }

  void add_wall(const btVector3& normal, double constant, double restitution) {
    wall_shapes.push_back(std::make_unique<btStaticPlaneShape>(normal, constant));
    btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, wall_shapes.back().get());
    info.m_friction = 0;
    info.m_rollingFriction = 0;
    info.m_spinningFriction = 0;
    info.m_restitution = restitution;  // Bullet multiplies: e_ball · e_wall, as motus
    walls.push_back(std::make_unique<btRigidBody>(info));
    world->addRigidBody(walls.back().get(), kWallGroup, kBallGroup | kPointGroup);
  }
};

BulletBackend::BulletBackend() { use_allocator_that_throws(); }
BulletBackend::~BulletBackend() = default;

std::string BulletBackend::version() const { return "Bullet 3.24, double"; }

void BulletBackend::build(const SceneDescription& scene, const Method& /*method*/, double dt) {
  if (!scene.mechanical) throw Unsupported("bullet", {"first-order systems (compare runs point masses)"});
  const MechanicalDescription& m = *scene.mechanical;

  std::vector<std::string> unsupported;
  if (m.dimensions < 1 || m.dimensions > 3) unsupported.push_back(std::to_string(m.dimensions) + "-D scenes");
  // A 2-D segment is a capsule wall with no inside that balls meet from both sides and
  // round its ends; a thin static box would have corners and a thickness, and a
  // btCapsuleShape is a solid: neither is the same wall.
  if (!m.colliders.segments.empty()) unsupported.push_back("segment colliders");
  // Every element it cannot express, not only the first (docs/cli.md: one line each). The bodies'
  // starts are read in the scene's dimensions, which need to be ones Bullet has.
  if (m.dimensions >= 1 && m.dimensions <= 3) {
    for (const auto& away : bodies_pinned_away(m))
      unsupported.push_back(away + " (motus moves it to the pin at the first step; Bullet makes it there)");
    // (Bullet pushed such a body out over some fifteen steps, with energy it did not have.)
    for (const auto& outside : bodies_starting_outside(m))
      unsupported.push_back(outside + " (motus moves it onto the wall's side; Bullet would push it out over several "
                                      "steps, with energy of its own)");
  }
  if (!unsupported.empty()) throw Unsupported("bullet", unsupported);

  auto w = std::make_unique<World>();
  w->d = m.dimensions;
  w->dt = dt;
  w->t0 = scene.start_time;
  w->config = std::make_unique<btDefaultCollisionConfiguration>();
  w->dispatcher = std::make_unique<btCollisionDispatcher>(w->config.get());
  w->broadphase = std::make_unique<btDbvtBroadphase>();
  w->solver = std::make_unique<btSequentialImpulseConstraintSolver>();
  w->world = std::make_unique<btDiscreteDynamicsWorld>(w->dispatcher.get(), w->broadphase.get(), w->solver.get(),
                                                       w->config.get());
  btContactSolverInfo& solver_info = w->world->getSolverInfo();
  solver_info.m_restitutionVelocityThreshold = kRestitutionVelocityThreshold;
  // Bullet's predictive (CCD) contacts carry restitution 0. Its remedy,
  // setApplySpeculativeContactRestitution(true) ("not well tested yet", Bullet's own
  // comment), re-applies e times their impulse after the step: it makes a fast ball
  // bounce off a wall at full speed, but two fast balls meeting head-on then stay stuck
  // at touching with their approach velocities, step after step (measured here at
  // ±100 m/s, 60 Hz). So it stays off, Bullet's default, and notes() says what that costs.

  w->forces.emplace(m);
  const auto& g = w->forces->gravity();
  const btVector3 gravity(g[0], w->d > 1 ? g[1] : 0, w->d > 2 ? g[2] : 0);
  w->world->setGravity(gravity);

  const btVector3 linear_factor(1, w->d > 1 ? 1 : 0, w->d > 2 ? 1 : 0);
  const size_t n = m.bodies.size();
  w->pinned.assign(n, false);
  std::vector<btVector3> pin_position(n);
  for (const auto& p : m.pins) {
    const auto i = static_cast<size_t>(p.body);
    w->pinned[i] = true;
    pin_position[i] = btVector3(p.position[0], w->d > 1 ? p.position[1] : 0, w->d > 2 ? p.position[2] : 0);
  }
  const bool has_walls = !m.colliders.empty();
  for (size_t i = 0; i < n; ++i) {
    const BodyDescription& b = m.bodies[i];
    const bool point = b.radius <= 0;
    const double radius = point ? kPointRadius : b.radius;
    const double mass = w->pinned[i] ? 0 : b.mass;  // a pinned body is static
    w->mass.push_back(b.mass);
    btSphereShape* shape = w->sphere(radius);
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
    info.m_startWorldTransform.setIdentity();
    info.m_startWorldTransform.setOrigin(w->pinned[i] ? pin_position[i] : w->to_bt(b.position));
    info.m_friction = 0;
    info.m_rollingFriction = 0;
    info.m_spinningFriction = 0;
    info.m_restitution = b.restitution;
    info.m_linearDamping = 0;
    info.m_angularDamping = 0;
    auto body = std::make_unique<btRigidBody>(info);
    if (mass > 0) {
      body->setLinearFactor(linear_factor);
      body->setAngularFactor(0);  // frictionless balls do not spin (no torque reaches them)
      body->setLinearVelocity(w->to_bt(b.velocity));
      if (!point) {
        // Continuous collision for balls once one moves more than its radius in a step
        // (what discrete detection could miss between two balls). Not for point masses:
        // they meet only walls, and a plane is a half-space that a body cannot cross
        // unnoticed; CCD's predictive contacts (restitution 0) would only cost them speed.
        body->setCcdMotionThreshold(radius);
        body->setCcdSweptSphereRadius(radius);
      }
    }
    body->setActivationState(DISABLE_DEACTIVATION);
    const int group = point ? kPointGroup : kBallGroup;
    const int mask = point ? kWallGroup : (kBallGroup | kWallGroup);
    w->world->addRigidBody(body.get(), group, mask);
    // addRigidBody copies the world's gravity into the body; set it again explicitly.
    if (mass > 0) body->setGravity(gravity);
    // A sphere meets a wall (btConvexPlaneCollisionAlgorithm) from a gap of up to the manifold's
    // breaking threshold on: Bullet's default dispatcher makes it relative
    // (CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD), the smaller of the two shapes'
    // gContactBreakingThreshold (0.02) times their bounding radius (√3·r for a sphere; a plane's is
    // huge). Measured: 0.0173 m for drop's ball of r = 0.5. (Two spheres meet only once they
    // overlap: btSphereSphereCollisionAlgorithm makes no contact at a gap, measured.)
    if (mass > 0 && has_walls) {
      const bool relative =
          (w->dispatcher->getDispatcherFlags() & btCollisionDispatcher::CD_USE_RELATIVE_CONTACT_BREAKING_THRESHOLD) != 0;
      const double threshold = relative ? shape->getContactBreakingThreshold(gContactBreakingThreshold)
                                        : static_cast<double>(gContactBreakingThreshold);
      if (threshold > w->contact_threshold) {
        w->contact_threshold = threshold;
        w->contact_threshold_radius = radius;
      }
    }
    w->bodies.push_back(std::move(body));
    if (point && has_walls) w->has_points_and_walls = true;
  }
  long balls = 0;
  for (const auto& b : m.bodies) balls += b.radius > 0 ? 1 : 0;
  w->has_contacts = balls > 1 || (has_walls && !m.bodies.empty());

  // Walls: each plane n·x ≥ offset is a btStaticPlaneShape (Bullet's plane n·x = c with
  // the solid below), each box container its 2·d inward faces.
  for (const auto& p : m.colliders.planes) {
    const double len = norm3(p.normal, w->d);
    btVector3 nrm(0, 0, 0);
    for (int k = 0; k < w->d; ++k) nrm[k] = p.normal[static_cast<size_t>(k)] / len;
    w->add_wall(nrm, p.offset / len, p.restitution);
  }
  for (const auto& box : m.colliders.boxes) {
    for (int k = 0; k < w->d; ++k) {
      btVector3 up(0, 0, 0);
      up[k] = 1;
      w->add_wall(up, box.min[static_cast<size_t>(k)], box.restitution);    // x_k ≥ min_k
      w->add_wall(-up, -box.max[static_cast<size_t>(k)], box.restitution);  // −x_k ≥ −max_k
    }
  }

  for (const auto& s : m.sticks) {
    const auto a = static_cast<size_t>(s.a), b = static_cast<size_t>(s.b);
    if (w->pinned[a] && w->pinned[b]) continue;  // both held: nothing can move
    auto c = std::make_unique<DistanceConstraint>(*w->bodies[a], *w->bodies[b], s.length);
    w->world->addConstraint(c.get(), /*disableCollisionsBetweenLinkedBodies=*/false);
    w->stick_bodies.emplace_back(a, b);
    w->stick_lengths.push_back(s.length);
    w->sticks.push_back(std::move(c));
  }

  world_ = std::move(w);
}

void BulletBackend::step() {
  World& w = *world_;
  const int d = w.d;
  const size_t n = w.bodies.size();
  if (!w.forces->empty()) {
    // The scene's other forces by motus's formulas at (t, x, v), as a force for the step.
    w.x.resize(n * static_cast<size_t>(d));
    w.v.resize(n * static_cast<size_t>(d));
    for (size_t i = 0; i < n; ++i) {
      const btVector3& p = w.bodies[i]->getCenterOfMassPosition();
      const btVector3& u = w.bodies[i]->getLinearVelocity();
      for (int k = 0; k < d; ++k) {
        w.x[i * static_cast<size_t>(d) + static_cast<size_t>(k)] = p[k];
        w.v[i * static_cast<size_t>(d) + static_cast<size_t>(k)] = u[k];
      }
    }
    w.forces->compute(w.t0 + static_cast<double>(w.steps) * w.dt, w.x, w.v, w.F);
    for (size_t i = 0; i < n; ++i) {
      if (w.pinned[i]) continue;
      btVector3 f(0, 0, 0);
      for (int k = 0; k < d; ++k) f[k] = w.F[i * static_cast<size_t>(d) + static_cast<size_t>(k)];
      w.bodies[i]->applyCentralForce(f);
    }
  }
  // Count the body-steps where CCD engages (motion this step above the threshold).
  for (size_t i = 0; i < n && watching_; ++i) {
    const btRigidBody& b = *w.bodies[i];
    if (b.getCcdSquareMotionThreshold() > 0 &&
        b.getLinearVelocity().length2() * w.dt * w.dt > b.getCcdSquareMotionThreshold())
      ++w.ccd_steps;
  }
  // maxSubSteps 0: exactly one internal step of dt, no accumulator, no interpolation.
  w.world->stepSimulation(w.dt, 0);
  ++w.steps;
  for (size_t j = 0; j < w.stick_bodies.size() && watching_; ++j) {
    const btScalar len = (w.bodies[w.stick_bodies[j].second]->getCenterOfMassPosition() -
                          w.bodies[w.stick_bodies[j].first]->getCenterOfMassPosition())
                             .length();
    const double error = std::abs(len - w.stick_lengths[j]) / w.stick_lengths[j];
    if (const double worst = worse(w.worst_stick_error, error); worst != w.worst_stick_error) {  // (NaN: the worst)
      w.worst_stick_error = worst;
      w.worst_stick_step = w.steps;
    }
  }
}

void BulletBackend::read(Snapshot& out) const {
  const World& w = *world_;
  const size_t n = w.bodies.size(), d = static_cast<size_t>(w.d);
  out.t = w.t0 + static_cast<double>(w.steps) * w.dt;
  out.x.resize(n * d);
  out.v.resize(n * d);
  for (size_t i = 0; i < n; ++i) {
    const btVector3& p = w.bodies[i]->getCenterOfMassPosition();
    const btVector3& u = w.bodies[i]->getLinearVelocity();
    for (size_t k = 0; k < d; ++k) {
      out.x[i * d + k] = p[static_cast<int>(k)];
      out.v[i * d + k] = u[static_cast<int>(k)];
    }
  }
}

std::vector<std::string> BulletBackend::settings() const {
  std::vector<std::string> s = {
      "step: world.stepSimulation(dt, 0) (maxSubSteps 0: exactly dt, no accumulator, no interpolation)",
      "bodies: btRigidBody + btSphereShape(radius); point masses btSphereShape(0.001 m), colliding with walls only",
      "sleep: off (DISABLE_DEACTIVATION)",
      "damping: linear 0, angular 0",
      "friction: 0 on bodies and walls (rolling, spinning 0)",
      "restitution: on bodies (their e) and walls (their e); Bullet mixes the product, as motus",
      "rotation: setAngularFactor(0)",
      "restitution velocity threshold: 0 m/s (Bullet's default 0.2 m/s)",
      "solver: sequential impulse, Bullet's defaults otherwise (10 iterations, warm starting 0.85, "
      "split impulse on below -0.04 m, contact ERP 0.2, joint ERP 0.2)",
      "CCD: motion threshold = radius, swept sphere = radius (speculative contact restitution off, the default)",
  };
  if (world_) {
    if (world_->d == 2) s.emplace_back("2-D: z = 0 plane, setLinearFactor(1, 1, 0)");
    if (world_->d == 1) s.emplace_back("1-D: x axis, setLinearFactor(1, 0, 0)");
    if (!world_->forces->empty()) s.emplace_back("forces: motus's formulas, applyCentralForce every step");
    if (!world_->sticks.empty()) s.emplace_back("sticks: one-row rigid distance constraints (Bullet's solver)");
  }
  return s;
}

std::vector<std::string> BulletBackend::notes() const {
  std::vector<std::string> n;
  if (!world_) return n;
  const World& w = *world_;
  if (w.has_contacts) {
    // The solver's target for a contact still a gap apart is e·v_in − gap/dt (the restitution,
    // less the closing of the gap within the step): drop (dt = 1 ms) met the floor 4.8 mm away and
    // left at 6.39 m/s where e = 0.8 gives 11.2 (test_compare_bullet). The figure for this run's dt.
    // (Without walls, or with no moving body to meet them, no contact is found at a gap.)
    const double threshold = w.contact_threshold;
    n.push_back(
        threshold > 0
            ? format("contacts are found by discrete detection at the end of the step, a body and a wall from a gap "
                     "of up to the contact breaking threshold on (%.3g m here: 0.02 times a sphere's bounding radius "
                     "sqrt(3)*r, for r = %g m), two balls once they overlap: the normal comes from the positions then, "
                     "not at the touching instant, and for a wall still a gap away the solver aims for a rebound "
                     "slower by gap/dt: at dt = %g s a rebound up to %.3g m / %g s = %.3g m/s slower, or none at all "
                     "where the rebound would be slower than that",
                     threshold, w.contact_threshold_radius, w.dt, threshold, w.dt, threshold / w.dt)
            : std::string("contacts are found by discrete detection at the end of the step, once two balls overlap: "
                          "the normal comes from the positions then, not at the touching instant"));
    n.emplace_back(
        "position correction: overlaps shallower than 0.04 m (split-impulse threshold) are pushed apart through "
        "the velocity (ERP 0.2 times the overlap per step), which adds kinetic energy; deeper ones by split "
        "impulse, which moves positions only");
  }
  if (w.has_points_and_walls)
    n.emplace_back("point masses are spheres of 0.001 m: they meet walls 0.001 m before their centre would");
  if (!w.sticks.empty())
    n.push_back(std::string("sticks are velocity constraints with Baumgarte correction (joint ERP 0.2): the length "
                            "drifts between steps and is pulled back, not projected as motus's Verlet sticks") +
                (w.steps > 0 ? format("; the worst length error so far is %.3g%% of the rest length (after step %ld)",
                                      100 * w.worst_stick_error, w.worst_stick_step)
                             : std::string()));
  if (w.ccd_steps > 0)
    n.emplace_back("CCD armed on " + std::to_string(w.ccd_steps) +
                   " body-steps (a body moving more than its radius in a step): Bullet sweeps it against the "
                   "others' start-of-step positions; when the sweep hits, it clamps the motion at the time of impact "
                   "(the rest of the step is lost) and adds a predictive contact with restitution 0. That stops "
                   "tunnelling but can lose energy at such a contact, whatever the bodies' e, by how much depending "
                   "on where in its step the contact falls (measured at 60 Hz): a ball at 100 m/s leaves a wall at "
                   "70 m/s from 5 m away, at 22 m/s from 4.2 m, at 4 m/s from 3.9 m; two balls meeting head-on at "
                   "100 m/s from +-3 m stop dead, from +-5 m bounce apart whole; a fast body that meets nothing is "
                   "not changed");
  // The π/4-per-step angular clamp never bites here: no body rotates (angular factor 0).
  return n;
}

}  // namespace motus::compare
