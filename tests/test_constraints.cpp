// Verlet sticks, pins and projected contacts (constrain/constraint_projection.hpp), on the
// scenes shipped in scenes/ — cloth.json, rope.json, ragdoll.json, stick_pendulum.json —
// built here in C++ with the same numbers (the scene generators are the engine's, the
// JSON loader is not part of the engine). Each number says where it comes from; the method
// is docs/course.md, section 10.
#include <gtest/gtest.h>

#include "motus/scene_file/scene_file.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <numbers>
#include <vector>

#include "motus/constrain/chain_solver.hpp"
#include "motus/constrain/constraint_projection.hpp"
#include "motus/constrain/stick_chains.hpp"
#include "motus/constrain/sweep_order.hpp"
#include "motus/ball_lattice.hpp"
#include "motus/scene_error.hpp"
#include "motus/scene_generators.hpp"
#include "motus/simulation.hpp"

// Every heap allocation in this program is counted, so that a test can check that a
// projection allocates nothing (docs/architecture.md: "a step allocates nothing").
namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
// GCC sees free() on memory from operator new and warns; here that pairing is the point.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace {

using motus::Integrator;
using motus::MechanicalDescription;
using motus::SceneDescription;
using motus::Simulation;
using motus::Vector;

constexpr double kG = 9.81;         // every scene: "g": [0, -9.81]
constexpr double kDt = 1.0 / 60.0;  // every scene: "dt" = 1/60 s

SceneDescription verlet_scene(const std::string& name, const MechanicalDescription& m, double duration) {
  SceneDescription s;
  s.name = name;
  s.integrator = "verlet";
  s.dt = kDt;
  s.duration = duration;
  s.mechanical = m;
  return s;
}

MechanicalDescription with_gravity(int iterations) {
  MechanicalDescription m;
  m.dimensions = 2;
  m.forces.gravity.push_back({{0, -kG, 0}});
  m.constraint_iterations = iterations;
  return m;
}

motus::PlaneCollider ground() { return {{0, 1, 0}, 0, 1}; }  // "normal": [0, 1], "offset": 0

// scenes/cloth.json.
constexpr int kClothIterations = 300;
SceneDescription cloth_scene(bool with_ground = true, int rows = 20, int columns = 20,
                             int iterations = kClothIterations) {
  MechanicalDescription m = with_gravity(iterations);
  motus::ClothGenerator c;
  c.rows = rows;
  c.columns = columns;
  c.spacing = 0.1;
  c.mass = 0.01;
  c.origin = {-0.95, 2.5, 0};
  c.shear = true;
  c.pin = "top-corners";
  motus::add_cloth(m, c);
  if (with_ground) m.colliders.planes.push_back(ground());
  return verlet_scene("cloth", m, 10);
}

// scenes/rope.json's rope: 20 sticks of 0.1 m from (0, 2), horizontal, the first particle pinned.
void add_shipped_rope(MechanicalDescription& m) {
  motus::RopeGenerator r;
  r.segments = 20;
  r.segment_length = 0.1;
  r.mass = 0.05;
  r.origin = {0, 2, 0};
  r.direction = {1, 0, 0};
  motus::add_rope(m, r);
}

// scenes/rope.json.
SceneDescription rope_scene() {
  MechanicalDescription m = with_gravity(120);
  add_shipped_rope(m);
  return verlet_scene("rope", m, 10);
}

// scenes/ragdoll.json: a standing figure lifted 1.5 m and thrown up and to the right, tumbling
// (spun at 6 rad/s clockwise about the point 0.9 m above its feet), into a 6 m × 4 m room.
struct Part {
  double x, y, radius, mass;
};
constexpr std::array<Part, 13> kRagdoll = {{
    {0, 1.75, 0.12, 5},      // head
    {0, 1.5, 0, 2},          // neck
    {-0.2, 1.45, 0, 3},      // left shoulder
    {0.2, 1.45, 0, 3},       // right shoulder
    {-0.3, 1.15, 0, 2},      // left elbow
    {0.3, 1.15, 0, 2},       // right elbow
    {-0.35, 0.85, 0.05, 1},  // left hand
    {0.35, 0.85, 0.05, 1},   // right hand
    {0, 0.95, 0, 10},        // pelvis
    {-0.1, 0.5, 0, 5},       // left knee
    {0.1, 0.5, 0, 5},        // right knee
    {-0.12, 0.05, 0.05, 2},  // left foot
    {0.12, 0.05, 0.05, 2},   // right foot
}};
constexpr std::array<std::array<int, 2>, 19> kRagdollSticks = {{
    {0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3},    // head and shoulders
    {2, 4}, {4, 6}, {3, 5}, {5, 7},                    // arms
    {1, 8}, {2, 8}, {3, 8},                            // torso
    {8, 9}, {9, 11}, {8, 10}, {10, 12},                // legs
    {2, 9}, {3, 10},                                   // shoulder to knee: the hips do not fold
}};
constexpr std::array<double, 2> kBoxMin{-3, 0}, kBoxMax{3, 4};
constexpr double kRagdollSpin = -6, kRagdollSpinAt = 0.9;  // rad/s, and the height it spins about

SceneDescription ragdoll_scene() {
  MechanicalDescription m = with_gravity(10);
  for (const Part& p : kRagdoll) {
    motus::BodyDescription b;
    b.mass = p.mass;
    b.position = {p.x - 1, p.y + 1.5};
    // (1, 3) m/s plus the spin ω × r about (0, kRagdollSpinAt) in the figure's own frame.
    b.velocity = {1 - kRagdollSpin * (p.y - kRagdollSpinAt), 3 + kRagdollSpin * p.x};
    b.radius = p.radius;
    m.bodies.push_back(b);
  }
  for (const auto& [a, b] : kRagdollSticks) {
    const double dx = kRagdoll[b].x - kRagdoll[a].x, dy = kRagdoll[b].y - kRagdoll[a].y;
    m.sticks.push_back({a, b, std::hypot(dx, dy)});  // the loader's default: the start distance
  }
  m.colliders.boxes.push_back({{kBoxMin[0], kBoxMin[1], 0}, {kBoxMax[0], kBoxMax[1], 0}, 0.3});
  return verlet_scene("ragdoll", m, 6);
}

// scenes/stick_pendulum.json: pivot pinned at the origin, bob on a stick of length L,
// released from rest at angle theta from straight down (the scene: theta = π/2).
constexpr double kL = 1;
SceneDescription stick_pendulum_scene(double theta = std::numbers::pi / 2, int iterations = 1) {
  MechanicalDescription m = with_gravity(iterations);
  m.bodies.push_back({1, {0, 0}, {0, 0}});
  m.bodies.push_back({1, {kL * std::sin(theta), -kL * std::cos(theta)}, {0, 0}});
  m.sticks.push_back({0, 1, kL});
  m.pins.push_back({0, {0, 0, 0}});
  return verlet_scene("stick_pendulum", m, 10);
}

// ---------------------------------------------------------------------------------
// The projection on its own: what one project() call does.

TEST(Projection, OneStickIsSolvedExactlyAndKeepsTheCentreOfMass) {
  // Two free bodies of masses 1 and 3 on a stick of length 1, stretched to 2: the
  // projection moves them along the stick by 3/4 and 1/4 of the error (inverse masses),
  // so the length is 1 and the centre of mass does not move (no momentum is made).
  Vector inverse_mass(2);
  inverse_mass << 1.0, 1.0 / 3.0;
  motus::ConstraintProjection p(2, inverse_mass, {0, 0}, {{0, 1, 1.0}}, {}, {}, 1);
  Vector x(4);
  x << 0, 0, 2, 0;
  const double centre = (1 * x[0] + 3 * x[2]) / 4;
  p.project(x);
  EXPECT_NEAR(x[2] - x[0], 1.0, 1e-15);  // theory: one projection of one stick is exact
  EXPECT_NEAR((1 * x[0] + 3 * x[2]) / 4, centre, 1e-15);
  EXPECT_NEAR(x[0], 0.75, 1e-15);  // the light body takes 3/4 of the 1 m error
  EXPECT_EQ(p.max_relative_stick_error(x), 0.0);
}

TEST(Projection, APinnedEndDoesNotMove) {
  Vector inverse_mass = Vector::Ones(2);
  motus::ConstraintProjection p(2, inverse_mass, {0, 0}, {{0, 1, 1.0}}, {{0, {0.5, 0.25, 0}}}, {}, 1);
  EXPECT_TRUE(p.pinned(0));
  EXPECT_FALSE(p.pinned(1));
  Vector x(4);
  x << 0.1, 0.2, 3, 0.25;
  p.project(x);
  EXPECT_EQ(x[0], 0.5);  // exactly on its pin
  EXPECT_EQ(x[1], 0.25);
  EXPECT_NEAR(std::hypot(x[2] - x[0], x[3] - x[1]), 1.0, 1e-15);  // the free end took all the error
}

TEST(Projection, WallsPushBodiesBackToTheirSurfaceAtTheirRadius) {
  motus::Colliders walls;
  walls.planes.push_back({{0, 2, 0}, 1, 1});                 // y ≥ 0.5 once the normal is made unit
  walls.boxes.push_back({{-1, -1, 0}, {1, 1, 0}, 1});         // stay inside [−1, 1]²
  walls.segments.push_back({{-0.5, 0.8, 0}, {0.5, 0.8, 0}, 1});  // a shelf at y = 0.8
  const Vector inverse_mass = Vector::Ones(3);
  motus::ConstraintProjection p(2, inverse_mass, {0.1, 0, 0}, {}, {}, walls, 1);
  Vector x(6);
  x << 1.5, 0.0,   // ball of radius 0.1: below the plane and outside the box's right face
      0.0, 0.75,   // point just under the shelf: not touching, it stays
      -3, 2;       // point far outside the box's corner
  p.project(x);
  EXPECT_DOUBLE_EQ(x[0], 0.9);  // box face x = 1, minus the radius
  EXPECT_DOUBLE_EQ(x[1], 0.6);  // plane y = 0.5, plus the radius
  EXPECT_EQ(x[2], 0.0);
  EXPECT_EQ(x[3], 0.75);
  EXPECT_EQ(x[4], -1.0);
  EXPECT_EQ(x[5], 1.0);
  // A point that crossed the shelf since the last projection goes back to its side.
  x[3] = 0.85;
  p.project(x);
  EXPECT_EQ(x[2], 0.0);
  EXPECT_DOUBLE_EQ(x[3], 0.8);  // on the surface, on the side it came from (radius 0)
}

TEST(Projection, OverlappingBallsSeparateMassWeightedThroughTheBroadPhase) {
  Vector inverse_mass(3);
  inverse_mass << 1.0, 1.0, 0.5;
  // Balls 0 and 1 overlap by 0.5; ball 2 is far away.
  motus::ConstraintProjection p(2, inverse_mass, {0.5, 0.5, 0.5}, {}, {}, {}, 1);
  Vector x(6);
  x << 0, 0, 0.5, 0, 10, 10;
  p.project(x);
  EXPECT_NEAR(x[0], -0.25, 1e-15);  // equal masses: each takes half of the 0.5 overlap
  EXPECT_NEAR(x[2], 0.75, 1e-15);
  EXPECT_EQ(x[4], 10.0);
  EXPECT_GT(p.broad_phase_queries(), 0);
  // Each ball looks into at most the 3² cells around it: never all pairs, never more.
  EXPECT_LE(p.broad_phase_queries(), 3 * 9);
}

TEST(Projection, BallsFlungFarBeyondAnyCellStillSeparate) {
  // Balls 0 and 1 at x = 1e12 (10¹² / 1.5 cells out: past the hash's ±1e6 cells, where the cell
  // index is clamped rather than cast out of range) overlap by 0.5; ball 2 at −1e300 (past int64's
  // range as a cell index) touches nobody. The clamped cells still bring the overlapping pair
  // together: equal masses each take half of the overlap, exactly as near the origin (to the
  // spacing of doubles at 1e12, 1.2e-4).
  motus::ConstraintProjection p(2, Vector::Ones(3), {0.5, 0.5, 0.5}, {}, {}, {}, 1);
  Vector x(6);
  x << 1e12, 0, 1e12 + 0.5, 0, -1e300, 0;
  p.project(x);
  EXPECT_NEAR(x[0], 1e12 - 0.25, 2e-4);
  EXPECT_NEAR(x[2], 1e12 + 0.75, 2e-4);
  EXPECT_EQ(x[4], -1e300);
}

TEST(Projection, OneBallNeedsNoBroadPhase) {
  motus::Colliders walls;
  walls.planes.push_back({{0, 1, 0}, 0, 1});
  motus::ConstraintProjection p(2, Vector::Ones(2), {0.5, 0}, {}, {}, walls, 4);
  Vector x(4);
  x << 0, 0, 1, -1;
  p.project(x);
  EXPECT_EQ(p.broad_phase_queries(), 0);  // fewer than two balls: no pair to look for
  EXPECT_DOUBLE_EQ(x[1], 0.5);
  EXPECT_EQ(x[3], 0.0);
}

TEST(Projection, AProjectionAllocatesNothing) {
  // The ragdoll's constraints (balls, walls, sticks): after the first call has sized
  // the candidate list, project() never touches the heap.
  const SceneDescription scene = ragdoll_scene();
  const auto& m = *scene.mechanical;
  Vector inverse_mass(static_cast<Eigen::Index>(m.bodies.size()));
  std::vector<double> radius;
  Vector x(2 * inverse_mass.size());
  for (size_t i = 0; i < m.bodies.size(); ++i) {
    inverse_mass[static_cast<Eigen::Index>(i)] = 1 / m.bodies[i].mass;
    radius.push_back(m.bodies[i].radius);
    x[static_cast<Eigen::Index>(2 * i)] = m.bodies[i].position[0];
    x[static_cast<Eigen::Index>(2 * i + 1)] = m.bodies[i].position[1] - 3.4;  // everything through the floor
  }
  motus::ConstraintProjection p(2, inverse_mass, radius, m.sticks, m.pins, m.colliders, 10);
  p.project(x);
  const long before = g_allocations.load();
  for (int call = 0; call < 100; ++call) {
    x.array() -= 0.01;
    p.project(x);
  }
  EXPECT_EQ(g_allocations.load() - before, 0);
}

// ---------------------------------------------------------------------------------
// The shipped scenes, run through Simulation and the World.

// The cloth is scenes/cloth.json itself, loaded as `motus run cloth` loads it, run once
// (about a second: 32 substeps of one sweep over 1 482 sticks for 1 440 steps); the tests
// below check its figures.
class ClothScene : public ::testing::Test {
protected:
  struct Figures {
    double worst_error = 0;     // the largest relative stick error after any step
    double worst_pin_move = 0;  // the largest distance of a pinned particle from its pin
    long steps = 0, expected_steps = 0;
    int iterations = 0;
    long broad_phase_queries = -1;
    std::vector<std::string> passes;
  };
  static void SetUpTestSuite() {
    const SceneDescription scene = motus::load_scene(MOTUS_SCENES_DIR "/cloth.json");
    const auto& m = *scene.mechanical;
    const int d = m.dimensions;
    Simulation sim(scene, Integrator::Verlet);
    Figures f;
    const long n = static_cast<long>(m.bodies.size()) * d;
    sim.advance(scene.duration, scene.dt, {}, [&](const Simulation& s) {
      const Vector& y = s.state();
      f.worst_error = std::max(f.worst_error, s.world()->constraint_error(y.head(n)));
      for (const auto& pin : m.pins)
        for (int k = 0; k < d; ++k)
          f.worst_pin_move = std::max(f.worst_pin_move, std::abs(y[pin.body * d + k] - pin.position[k]));
    });
    f.steps = sim.steps();
    f.expected_steps = motus::fixed_step_count(scene.duration, scene.dt);
    f.iterations = m.constraint_iterations;
    f.broad_phase_queries = sim.world()->collision_counters().broad_phase_queries();
    f.passes = sim.world()->passes();
    std::printf("  cloth.json, %d substeps of %d sweep(s): largest stick error %.4f%% over %ld steps\n",
                m.constraint_substeps, f.iterations, 100 * f.worst_error, f.steps);
    figures_ = f;
  }
  static Figures figures_;
};
ClothScene::Figures ClothScene::figures_;

TEST_F(ClothScene, StickErrorStaysBelowOnePercentAtEveryStep) {
  // The requirement (issue 3): < 1 % stretch with the configured projection (cloth.json: 32
  // substeps of one sweep, in colours, at 240 Hz). Measured: 0.59 % (28 substeps: 0.93 %;
  // 100 sweeps of one step in the scene's order, the scene before: 0.76 %; docs/course.md,
  // section 10, has the error against the cost).
  EXPECT_EQ(figures_.steps, figures_.expected_steps);
  EXPECT_LT(figures_.worst_error, 0.01);
}

TEST_F(ClothScene, PinnedParticlesNeverMove) {
  EXPECT_EQ(figures_.worst_pin_move, 0.0);  // pins are placed last, exactly
}

TEST_F(ClothScene, NoBroadPhaseWithoutBalls) {
  // Point masses and one plane: walls are checked body by body; with no two balls there
  // are no pairs to look for, and the counters show that no grid cell was looked into.
  EXPECT_EQ(figures_.broad_phase_queries, 0);
  EXPECT_EQ(figures_.passes.back(), "constraints and contacts (projection)");
}

TEST(Cloth, WithoutCollidersTheWorldRunsNoCollisionPass) {
  const SceneDescription scene = cloth_scene(/*with_ground=*/false, 6, 6, 20);
  Simulation sim(scene, Integrator::Verlet);
  sim.advance(1, scene.dt, {});
  EXPECT_FALSE(sim.world()->has_collisions());
  EXPECT_TRUE(sim.world()->has_constraints());
  EXPECT_EQ(sim.world()->passes(), (std::vector<std::string>{"forces", "drift", "constraints (projection)"}));
  EXPECT_EQ(sim.world()->collision_counters().broad_phase_queries(), 0);
}

TEST(Cloth, GeneratorMakesTheGridItsSticksAndPins) {
  MechanicalDescription m;
  motus::ClothGenerator c;
  c.rows = 3;
  c.columns = 4;
  c.spacing = 0.5;
  c.origin = {1, 2, 0};
  motus::add_cloth(m, c);
  ASSERT_EQ(m.bodies.size(), 12u);
  // 3·3 horizontal + 2·4 vertical structural sticks, 2·(2·3) diagonals.
  EXPECT_EQ(m.sticks.size(), 9u + 8u + 12u);
  EXPECT_EQ(m.bodies[5].position, (std::vector<double>{1.5, 1.5}));  // row 1, column 1
  ASSERT_EQ(m.pins.size(), 2u);                                      // the top corners
  EXPECT_EQ(m.pins[1].body, 3);
  for (const auto& s : m.sticks)
    EXPECT_TRUE(std::abs(s.length - 0.5) < 1e-15 || std::abs(s.length - 0.5 * std::sqrt(2.0)) < 1e-15);
  c.pin = "top-row";
  c.shear = false;
  MechanicalDescription row;
  motus::add_cloth(row, c);
  EXPECT_EQ(row.pins.size(), 4u);
  EXPECT_EQ(row.sticks.size(), 17u);
  c.pin = "corners";
  EXPECT_THROW(motus::add_cloth(row, c), motus::SceneError);
}

TEST(Rope, StickErrorStaysBelowOnePercentAndTheEndStaysPinned) {
  // rope.json: 120 sweeps at most. The rope is a chain, which motus solves all at once
  // (chain_solver.hpp) until it is exact: measured 1e-12 (Jakobsen's sweeps alone, as a
  // plug-in's projection runs them: 0.81 %; 100 sweeps: 1.05 %; 40: 3.1 %). The free end whips
  // through the bottom of the swing; that is where the error peaks.
  const SceneDescription scene = rope_scene();
  Simulation sim(scene, Integrator::Verlet);
  double worst = 0;
  sim.advance(scene.duration, scene.dt, {}, [&](const Simulation& s) {
    worst = std::max(worst, s.world()->constraint_error(s.state().head(42)));
    ASSERT_EQ(s.state()[0], 0.0);  // the pinned first particle, exactly at its start
    ASSERT_EQ(s.state()[1], 2.0);
  });
  std::printf("  rope, 120 sweeps: largest stick error %.4f%%\n", 100 * worst);
  EXPECT_LT(worst, 0.01);
}

TEST(StickPendulum, OneSweepKeepsTheLengthToRounding) {
  // One stick with one end pinned: a single projection puts the bob exactly at distance L
  // (theory), so stick_pendulum.json needs constraint_iterations = 1; what is left is
  // rounding, far below the 1e-9 asked for.
  const SceneDescription scene = stick_pendulum_scene();
  Simulation sim(scene, Integrator::Verlet);
  double worst = 0;
  sim.advance(scene.duration, scene.dt, {}, [&](const Simulation& s) {
    worst = std::max(worst, s.world()->constraint_error(s.state().head(4)));
    ASSERT_EQ(s.state()[0], 0.0);
    ASSERT_EQ(s.state()[1], 0.0);
  });
  std::printf("  stick pendulum from horizontal: largest relative length error %.3g\n", worst);
  EXPECT_LT(worst, 1e-9);
}

// Why the projected pendulum is not plain Verlet. Near the bottom, with θ small, the
// Verlet step predicts the bob at x̃ = 2x_n − x_{n−1} + h²g; its horizontal part is
// L(2θ_n − θ_{n−1}) and its depth L + h²g (gravity pulls it h²g further down). The
// projection puts it back on the circle along the line to the pivot, so
//   θ_{n+1} = (2θ_n − θ_{n−1}) / (1 + a),   a = (ωh)², ω² = g/L,
// where plain Verlet has θ_{n+1} = 2θ_n − θ_{n−1} − aθ_n. The roots λ of
// (1 + a)λ² − 2λ + 1 = 0 have |λ|² = 1/(1 + a) and arg λ = ωh(1 − a/3 + O(a²)):
//   the period is long by (ωh)²/3 (an O(h²) error: 9.1e-4 at h = 1/60), and
//   the amplitude shrinks by (1 + a)^(−1/2) per step: the projection damps — Jakobsen's
//   method trades energy for stability (plain Verlet's period is short by (ωh)²/24 and
//   its amplitude stays).
struct Swing {
  double period = 0;           // mean over the measured periods
  std::vector<double> peaks;   // the bob's largest |x| in each half swing
};

// Upward crossings of x = 0 by the bob (linear interpolation between steps: the bob
// moves at its fastest and straightest there).
Swing measure_swing(double theta, double dt, int periods) {
  SceneDescription scene = stick_pendulum_scene(theta);
  Simulation sim(scene, Integrator::Verlet);
  std::vector<double> crossings;
  Swing swing;
  double previous_x = scene.mechanical->bodies[1].position[0], previous_t = 0, peak = std::abs(previous_x);
  const double T0 = 2 * std::numbers::pi * std::sqrt(kL / kG);
  sim.advance((periods + 1.5) * T0, dt, {}, [&](const Simulation& s) {
    const double x = s.state()[2];
    if (previous_x < 0 && x >= 0)
      crossings.push_back(previous_t + (s.time() - previous_t) * -previous_x / (x - previous_x));
    if ((previous_x < 0) != (x < 0)) {
      swing.peaks.push_back(peak);
      peak = 0;
    }
    peak = std::max(peak, std::abs(x));
    previous_x = x;
    previous_t = s.time();
  });
  EXPECT_GE(static_cast<int>(crossings.size()), periods + 1);
  swing.period = (crossings[static_cast<size_t>(periods)] - crossings[0]) / periods;
  return swing;
}

TEST(StickPendulum, SmallAmplitudePeriodIsTwoPiRootLOverGToVerletsAccuracy) {
  const double theta = 0.01;  // rad: the amplitude correction θ²/16 = 6e-6 is kept out by K(k) below
  const double T0 = 2 * std::numbers::pi * std::sqrt(kL / kG);
  // The exact period at this amplitude, 4 √(L/g) K(sin θ/2) (→ 2π √(L/g) as θ → 0).
  const double T = 4 * std::sqrt(kL / kG) * std::comp_ellint_1(std::sin(theta / 2));
  const double Th = measure_swing(theta, kDt, 10).period;
  const double Th2 = measure_swing(theta, kDt / 2, 10).period;
  const double a = kG / kL * kDt * kDt;  // (ωh)²
  std::printf("  stick pendulum, theta0 = %.2f: 2pi sqrt(L/g) = %.9f s, exact %.9f s, Verlet dt = 1/60: %.9f s "
              "(%+.3g; theory (wh)^2/3 = %.3g), dt = 1/120: %.9f s (%+.3g)\n",
              theta, T0, T, Th, Th / T - 1, a / 3, Th2, Th2 / T - 1);
  // The theory above: long by (ωh)²/3, to within its O(a²) terms and the interpolation
  // (10 % allowed).
  EXPECT_NEAR(Th / T - 1, a / 3, 0.1 * a / 3);
  // Against 2π √(L/g) itself: that O(h²) error plus the amplitude's θ²/16.
  EXPECT_LT(std::abs(Th / T0 - 1), 1.1 * a / 3 + theta * theta / 16);
  // Second order: halving h divides the error by 4 (3.5 to 4.5 allowed).
  const double ratio = (Th / T - 1) / (Th2 / T - 1);
  EXPECT_GT(ratio, 3.5);
  EXPECT_LT(ratio, 4.5);
}

TEST(StickPendulum, ProjectionDampsTheSwingAsTheTheorySays) {
  // The amplitude falls by (1 + (ωh)²)^(−1/2) per step (the theory above): after N steps
  // from the first peak to the last, the ratio of the peaks is (1 + a)^(−N/2).
  const double theta = 0.01;
  const Swing swing = measure_swing(theta, kDt, 10);
  ASSERT_GE(swing.peaks.size(), 20u);
  const double a = kG / kL * kDt * kDt;
  const double half_periods = static_cast<double>(swing.peaks.size() - 2);
  const double steps = half_periods * swing.period / 2 / kDt;
  const double expected = std::pow(1 + a, -steps / 2);
  const double measured = swing.peaks.back() / swing.peaks[1];
  std::printf("  stick pendulum damping over %.0f steps: peaks fell to %.4f of the first, theory %.4f\n", steps,
              measured, expected);
  // The peaks are sampled at steps (within ωh/2 of the true peak: cos error < a/8 = 3e-4)
  // and the theory drops O(a²) terms: 1 % allowed.
  EXPECT_NEAR(measured / expected, 1.0, 0.01);
}

TEST(Ragdoll, NoParticleEverEndsUpInTheFloorOrOutsideTheBox) {
  const SceneDescription scene = ragdoll_scene();
  Simulation sim(scene, Integrator::Verlet);
  double lowest_gap = INFINITY;
  sim.advance(scene.duration, scene.dt, {}, [&](const Simulation& s) {
    const Vector& y = s.state();
    for (size_t i = 0; i < kRagdoll.size(); ++i) {
      const double r = kRagdoll[i].radius;
      const double x = y[static_cast<Eigen::Index>(2 * i)], h = y[static_cast<Eigen::Index>(2 * i + 1)];
      lowest_gap = std::min(lowest_gap, h - r);
      ASSERT_GE(h, kBoxMin[1] + r - 1e-12) << "body " << i << " at t = " << s.time();  // the floor
      ASSERT_GE(x, kBoxMin[0] + r - 1e-12) << "body " << i;              // the box's side walls
      ASSERT_LE(x, kBoxMax[0] - r + 1e-12) << "body " << i;
      ASSERT_LE(h, kBoxMax[1] - r + 1e-12) << "body " << i;
    }
  });
  // (Its sticks are held against both peers' in the same run, every step sampled, by
  // Compare.OnTheStickScenesMotusKeepsItsSticksAtLeastAsWellAsBothPeers.)
  std::printf("  ragdoll: lowest gap to the floor %.3g m\n", lowest_gap);
  EXPECT_LT(lowest_gap, 1e-3);  // it did land (the test would be empty otherwise)
  // Five balls (head, hands, feet): the broad phase ran, and the counters show it.
  EXPECT_GT(sim.world()->collision_counters().broad_phase_queries(), 0);
}

// The README's picture: the shipped ragdoll lands on its back and is still a ragdoll at the end —
// every stick at its length (within 1 %), lying on the floor, and not a heap: its head more than
// half its standing height from its feet (sticks are its only bones; the 17-stick figure thrown
// at the wall folded up with its head 0.25 m from its feet, 15 %; with shoulder-to-knee sticks the
// hips cannot fold, and only the knees can bend, which leaves at least 0.8 m).
TEST(Ragdoll, TheShippedOneLandsAndStaysARagdoll) {
  const SceneDescription scene = motus::load_scene(MOTUS_SCENES_DIR "/ragdoll.json");
  const SceneDescription described = ragdoll_scene();
  const auto& bodies = scene.mechanical->bodies;
  const auto& sticks = scene.mechanical->sticks;
  ASSERT_EQ(bodies.size(), kRagdoll.size());
  ASSERT_EQ(sticks.size(), kRagdollSticks.size());
  for (size_t i = 0; i < bodies.size(); ++i) {  // the file is the figure described above
    const auto& d = described.mechanical->bodies[i];
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(bodies[i].position[k], d.position[k], 1e-12) << "body " << i;
      EXPECT_NEAR(bodies[i].velocity[k], d.velocity[k], 1e-12) << "body " << i;
    }
  }
  Simulation sim(scene, Integrator::Verlet);
  const double kinetic_at_start = sim.energy()->kinetic;
  sim.advance(scene.duration, scene.dt, {});
  const Vector& y = sim.state();
  auto at = [&](int i) { return Eigen::Vector2d(y[2 * i], y[2 * i + 1]); };
  const double end_error = sim.world()->constraint_error(y.head(26));
  const double head_to_feet = (at(0) - 0.5 * (at(11) + at(12))).norm();
  const double standing = kRagdoll[0].y - kRagdoll[11].y;
  std::printf("  ragdoll at t = 6 s: stick error %.3f%%, head to feet %.3f m (standing %.2f m), "
              "kinetic energy %.3g of the start's, head at height %.3f m\n",
              100 * end_error, head_to_feet, standing, sim.energy()->kinetic / kinetic_at_start, at(0).y());
  EXPECT_LT(end_error, 0.01);
  EXPECT_GT(head_to_feet, 0.5 * standing);
  EXPECT_LT(at(0).y(), 0.5);  // it lies on the floor, not standing or sitting
}

// ---------------------------------------------------------------------------------
// The order of a sweep, chains solved at once, substeps.

// A sweep in the plain scene order, one stick after another, with the projection's arithmetic
// (shares w/(w_a + w_b), correction (d − L)/d · Δ): the reference the groups must reproduce.
void reference_sweep(const std::vector<motus::StickConstraint>& sticks, const Vector& w, Vector& x, int d) {
  for (const auto& s : sticks) {
    const double share_a = w[s.a] / (w[s.a] + w[s.b]), share_b = w[s.b] / (w[s.a] + w[s.b]);
    double delta[3], length2 = 0;
    for (int k = 0; k < d; ++k) {
      delta[k] = x[s.b * d + k] - x[s.a * d + k];
      length2 += delta[k] * delta[k];
    }
    const double length = std::sqrt(length2);
    const double stretch = (length - s.length) / length;
    for (int k = 0; k < d; ++k) {
      x[s.a * d + k] += stretch * share_a * delta[k];
      x[s.b * d + k] -= stretch * share_b * delta[k];
    }
  }
}

// The cloth of cloth.json's generator, crumpled: every body moved off the grid a little.
MechanicalDescription crumpled_cloth(int rows, int columns) {
  MechanicalDescription m;
  m.dimensions = 3;
  motus::ClothGenerator c;
  c.rows = rows;
  c.columns = columns;
  c.spacing = 0.1;
  c.plane = "xz";
  c.pin = "none";
  motus::add_cloth(m, c);
  std::uint64_t random = 7;
  for (auto& b : m.bodies)
    for (double& p : b.position) p += 0.02 * (motus::splitmix64_uniform(random) - 0.5);
  return m;
}

Vector positions(const MechanicalDescription& m) {
  Vector x(static_cast<Eigen::Index>(m.bodies.size()) * m.dimensions);
  for (size_t i = 0; i < m.bodies.size(); ++i)
    for (int k = 0; k < m.dimensions; ++k) x[static_cast<Eigen::Index>(i) * m.dimensions + k] = m.bodies[i].position[k];
  return x;
}

TEST(SweepOrder, GroupsShareNoBodyAndHoldEveryStickOnce) {
  const MechanicalDescription m = crumpled_cloth(20, 20);
  for (const auto order : {motus::SweepOrder::scene, motus::SweepOrder::colours}) {
    const auto groups = motus::sweep_groups(m.sticks, static_cast<int>(m.bodies.size()), order);
    std::vector<int> seen(m.sticks.size(), 0);
    for (int g = 0; g < groups.groups(); ++g) {
      std::vector<int> bodies;
      for (int u = groups.group_start[static_cast<size_t>(g)]; u < groups.group_start[static_cast<size_t>(g) + 1]; ++u) {
        const auto& s = m.sticks[static_cast<size_t>(groups.order[static_cast<size_t>(u)])];
        ++seen[static_cast<size_t>(groups.order[static_cast<size_t>(u)])];
        bodies.push_back(s.a);
        bodies.push_back(s.b);
      }
      std::sort(bodies.begin(), bodies.end());
      EXPECT_EQ(std::adjacent_find(bodies.begin(), bodies.end()), bodies.end()) << "group " << g;
    }
    for (int n : seen) EXPECT_EQ(n, 1);
    // A body of the cloth's interior has 8 sticks: a greedy colouring needs at least 8 colours
    // and at most 2·8 − 1 (theory); the scene's order needs far more levels.
    if (order == motus::SweepOrder::colours) {
      EXPECT_GE(groups.groups(), 8);
      EXPECT_LE(groups.groups(), 15);
    }
  }
}

TEST(SweepOrder, LevelsGiveTheScenesOrderToTheLastBit) {
  // A Gauss–Seidel sweep level by level: every stick still runs after exactly the earlier
  // sticks it shares a body with (theory: sweep_order.hpp), so the numbers are the scene order's
  // bit for bit — the projection's 40 sweeps against the plain sweep above, on a crumpled cloth.
  const MechanicalDescription m = crumpled_cloth(12, 9);
  const Vector w = Vector::Ones(static_cast<Eigen::Index>(m.bodies.size()));
  Vector mine = positions(m), reference = mine;
  motus::ConstraintProjection p(3, w, std::vector<double>(m.bodies.size(), 0.0), m.sticks, {}, {}, 40);
  p.project(mine);
  for (int sweep = 0; sweep < 40; ++sweep) reference_sweep(m.sticks, w, reference, 3);
  for (Eigen::Index i = 0; i < mine.size(); ++i) ASSERT_EQ(mine[i], reference[i]) << "coordinate " << i;
}

TEST(SweepOrder, AChainIsOneStickPerLevelAndTwoColours) {
  std::vector<motus::StickConstraint> chain;
  for (int i = 0; i < 10; ++i) chain.push_back({i, i + 1, 1.0});
  EXPECT_EQ(motus::sweep_groups(chain, 11, motus::SweepOrder::scene).groups(), 10);   // each waits for the last
  EXPECT_EQ(motus::sweep_groups(chain, 11, motus::SweepOrder::colours).groups(), 2);  // red–black
}

TEST(StickChains, FindsChainsAndNothingWithABranchOrALoop) {
  const Vector w = Vector::Ones(12);
  // 0–1–2–3 (listed out of order), a triangle 4–5–6, a Y 7–8, 8–9, 8–10, and 11 alone.
  const std::vector<motus::StickConstraint> sticks = {{2, 3, 1}, {0, 1, 1}, {4, 5, 1}, {1, 2, 1}, {5, 6, 1},
                                                      {6, 4, 1}, {7, 8, 1}, {8, 9, 1}, {8, 10, 1}};
  const auto chains = motus::find_stick_chains(sticks, w, 2);
  ASSERT_EQ(chains.size(), 1u);
  EXPECT_EQ(chains[0].bodies, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(chains[0].sticks, (std::vector<int>{1, 3, 0}));
  // A stick between two pinned bodies links nothing: 0–1 pinned at both ends splits the chain.
  Vector pinned = Vector::Ones(4);
  pinned[1] = pinned[2] = 0;
  const auto split = motus::find_stick_chains({{0, 1, 1}, {1, 2, 1}, {2, 3, 1}}, pinned, 1);
  ASSERT_EQ(split.size(), 2u);
  EXPECT_EQ(split[0].sticks, (std::vector<int>{0}));
  EXPECT_EQ(split[1].sticks, (std::vector<int>{2}));
  // The cloth has no chain at all: every body has three or more sticks.
  const MechanicalDescription cloth = crumpled_cloth(5, 5);
  EXPECT_TRUE(motus::find_stick_chains(cloth.sticks, Vector::Ones(25), 2).empty());
}

TEST(ChainSolver, NewtonSquaresTheErrorKeepsTheCentreOfMassAndAllocatesNothing) {
  // A free chain of 10 sticks of 1 m, masses 1..11, bent and stretched by up to 20 %: each
  // iteration of Newton's method at least squares the largest relative error (theory, up to a
  // constant: allowed 10·e²), and x ← x + W Jᵀ λ moves no centre of mass (Σ m_i W_i (Jᵀλ)_i =
  // Σ_j λ_j (n_j − n_j) = 0).
  const int n = 11;
  Vector w(n), x(2 * n);
  std::vector<motus::StickConstraint> sticks;
  std::uint64_t random = 3;
  for (int i = 0; i < n; ++i) {
    w[i] = 1.0 / (i + 1);
    const double stretch = 1 + 0.2 * (motus::splitmix64_uniform(random) - 0.5);
    x[2 * i] = i * stretch;
    x[2 * i + 1] = 0.3 * std::sin(i);
    if (i > 0) sticks.push_back({i - 1, i, 1.0});
  }
  auto centre = [&](const Vector& p) {
    Eigen::Vector2d c(0, 0);
    for (int i = 0; i < n; ++i) c += p.segment<2>(2 * i) / w[i];
    return c;
  };
  auto worst = [&](const Vector& p) {
    double e = 0;
    for (const auto& s : sticks) e = std::max(e, std::abs((p.segment<2>(2 * s.b) - p.segment<2>(2 * s.a)).norm() - s.length));
    return e;
  };
  const Eigen::Vector2d c0 = centre(x);
  motus::ChainSolver solver(2, w, sticks, motus::find_stick_chains(sticks, w, 2));
  double error = worst(x);
  std::printf("  chain of 10 sticks, Newton:");
  int iterations = 0;
  const long before = g_allocations.load();
  while (!solver.iterate(x.data(), 1e-12)) {
    const double next = worst(x);
    std::printf(" %.1e", next);
    EXPECT_LE(next, std::max(10 * error * error, 1e-14)) << "iteration " << iterations;
    error = next;
    ASSERT_LT(++iterations, 10);
  }
  std::printf("\n");
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_LT(worst(x), 1e-12);
  EXPECT_LE(iterations, 6);
  EXPECT_NEAR((centre(x) - c0).norm(), 0, 1e-12);
}

TEST(ChainSolver, APinAtEachEndStaysExactAndTheChainIsSolved) {
  // rope.json's rope, stretched between two pins 2.4 m apart: 20 sticks of 0.1 m cannot reach,
  // and no projection can make them. Hung slack between pins 1.8 m apart instead, and started
  // from a straight line, the chain solver makes every stick exact and leaves both pins.
  MechanicalDescription m = with_gravity(50);
  add_shipped_rope(m);
  m.pins.push_back({20, {1.8, 2, 0}});
  for (int i = 0; i <= 20; ++i) m.bodies[static_cast<size_t>(i)].position[0] = 0.09 * i;  // squeezed onto the line
  m.bodies[10].position[1] = 1.9;  // and the middle pulled down, so there is a way to bend
  SceneDescription scene = verlet_scene("slack rope", m, 2);
  Simulation sim(scene, Integrator::Verlet);
  double worst = 0;
  sim.advance(scene.duration, scene.dt, {}, [&](const Simulation& s) {
    worst = std::max(worst, s.world()->constraint_error(s.state().head(42)));
    ASSERT_EQ(s.state()[0], 0.0);
    ASSERT_EQ(s.state()[40], 1.8);
  });
  EXPECT_LT(worst, 1e-11);
}

TEST(ChainSolver, AChainThatCannotReachBetweenItsPinsStaysStretchedAndGainsNoEnergy) {
  // rope.json's rope (20 sticks of 0.1 m, 1 kg in all) stretched between pins 4 m apart: no
  // projection can make its sticks exact — every one is, on average, twice its length at least
  // (a relative error ≥ 1). Pulled straight along the line between its pins, the chain's
  // constraints are one too many for that line, Newton's system is near singular, and its steps
  // flung the bodies metres a step: Verlet read that as speed, and the energy grew without end
  // (an audit's chain of 10 sticks gained 458 J from 0 in 2 s). Now such a step is a sweep's: the
  // chain stays on the line between its pins (within a stick's length of it), its energy within
  // what gravity could give it over that length (m g × 4 m = 39 J; it starts at E = 0 on the
  // line), and its sticks' error near the least possible.
  MechanicalDescription m = with_gravity(50);
  add_shipped_rope(m);
  for (int i = 0; i <= 20; ++i) m.bodies[static_cast<size_t>(i)].position[0] = 0.2 * i;  // stretched to twice their length
  m.pins.push_back({20, {4, 2, 0}});
  const SceneDescription scene = verlet_scene("stretched rope", m, 4);
  Simulation sim(scene, Integrator::Verlet);
  const double e0 = sim.energy()->total, mass = 21 * 0.05, scale = mass * kG * 4;
  double worst_gain = 0, farthest_off_line = 0;
  sim.advance(scene.duration, scene.dt, {}, [&](const Simulation& s) {
    worst_gain = std::max(worst_gain, s.energy()->total - e0);
    for (int i = 0; i <= 20; ++i) farthest_off_line = std::max(farthest_off_line, std::abs(s.state()[2 * i + 1] - 2));
  });
  EXPECT_LT(worst_gain, scale);
  EXPECT_LT(farthest_off_line, 0.1);
  const double end_error = sim.world()->constraint_error(sim.state().head(42));
  EXPECT_GE(end_error, 1.0 - 1e-12);  // (the least possible: no projection gets below it)
  EXPECT_LT(end_error, 2.0);          // (twice that)
}

TEST(Rope, TheChainSolverKeepsItExact) {
  // rope.json through the chain solver (theory: Newton's method converges to rounding; its
  // tolerance is 1e-12 of a stick's length).
  const SceneDescription scene = rope_scene();
  Simulation sim(scene, Integrator::Verlet);
  double worst = 0;
  sim.advance(scene.duration, scene.dt, {}, [&](const Simulation& s) {
    worst = std::max(worst, s.world()->constraint_error(s.state().head(42)));
  });
  EXPECT_LT(worst, 1e-11);
}

TEST(Substeps, NSubstepsAreTheSameRunAsNTimesTheSteps) {
  // constraint_substeps = 4 at 1/60 s is the stick pendulum stepped at 1/240 s (one stick:
  // the sweep order changes nothing), to the last bit: the substeps are Verlet steps of dt/4,
  // each with its projection.
  SceneDescription four = stick_pendulum_scene();
  four.mechanical->constraint_substeps = 4;
  SceneDescription fine = stick_pendulum_scene();
  Simulation a(four, Integrator::Verlet), b(fine, Integrator::Verlet);
  a.advance(10, kDt, {});
  b.advance(10, kDt / 4, {});
  ASSERT_EQ(a.steps() * 4, b.steps());
  for (Eigen::Index i = 0; i < a.state().size(); ++i) EXPECT_EQ(a.state()[i], b.state()[i]) << i;
  // docs/course.md, section 10: from 0 J the total energy falls to −5.01 J in 10 s at 1/240 s;
  // tests/reference/stick_pendulum_energy.py, the same Verlet and projection in plain Python,
  // gives −5.0110828421 J (the same sums in another order: rounding alone parts them).
  EXPECT_NEAR(a.energy()->total, -5.0110828421, 1e-9);
  EXPECT_EQ(a.evaluations(), b.evaluations());  // one force evaluation per substep
}

TEST(Substeps, PinsStayExactAndAStepAllocatesNothing) {
  SceneDescription scene = motus::load_scene(MOTUS_SCENES_DIR "/cloth.json");
  ASSERT_GT(scene.mechanical->constraint_substeps, 1);
  scene.duration = 0.2;
  Simulation sim(scene, Integrator::Verlet);
  sim.advance(scene.dt, scene.dt, {});  // the first step sizes everything
  const long before = g_allocations.load();
  sim.advance(scene.duration, scene.dt, {});
  EXPECT_EQ(g_allocations.load() - before, 0);
  const int d = scene.mechanical->dimensions;
  for (const auto& pin : scene.mechanical->pins)
    for (int k = 0; k < d; ++k) EXPECT_EQ(sim.state()[pin.body * d + k], pin.position[k]);
}

TEST(Substeps, MustBeAtLeastOne) {
  SceneDescription scene = stick_pendulum_scene();
  scene.mechanical->constraint_substeps = 0;
  EXPECT_THROW(Simulation(scene, Integrator::Verlet), motus::SceneError);
}

TEST(Constraints, NeedVerlet) {
  EXPECT_THROW(Simulation(stick_pendulum_scene(), Integrator::Rk4), motus::SceneError);
}

// ---------------------------------------------------------------------------------
// The ball pairs' broad phase: a neighbour list kept across projections, rebuilt once a ball
// has moved half its skin (ball_pair_neighbours.cpp).

// A ball gas for the projection alone: ball_gas.json's lattice (ball_lattice.hpp), its positions
// and velocityless Verlet's other state, the positions one step of dt earlier. `spread` gives the
// balls radii from (1 − spread)·r to r and masses from 1 to 1 + 2·spread kg; `shuffled` numbers
// them in a random order (ball_lattice.hpp), so that a ball's number says nothing of where it is.
struct Gas {
  int d = 2;
  Vector x, previous, next, inverse_mass;
  std::vector<double> radius;
  motus::Colliders box;
};

Gas lattice_gas(int d, long count, double spacing, double speed, double spread = 0, bool shuffled = false) {
  MechanicalDescription m;
  m.dimensions = d;
  motus::BallLattice lattice;
  lattice.count = count;
  lattice.spacing = spacing;
  lattice.speed = speed;
  motus::add_ball_lattice(m, lattice);
  if (shuffled) motus::shuffle_bodies(m.bodies, 5);
  Gas g;
  g.d = d;
  const auto n = static_cast<Eigen::Index>(m.bodies.size());
  g.x.resize(d * n);
  g.previous.resize(d * n);
  g.next.resize(d * n);
  g.inverse_mass.resize(n);
  g.box = m.colliders;
  std::uint64_t random = 11;
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto& b = m.bodies[static_cast<size_t>(i)];
    g.radius.push_back(b.radius * (1 - spread * motus::splitmix64_uniform(random)));
    g.inverse_mass[i] = 1 / (b.mass * (1 + 2 * spread * motus::splitmix64_uniform(random)));
    for (int k = 0; k < d; ++k) {
      g.x[d * i + k] = b.position[static_cast<size_t>(k)];
      g.previous[d * i + k] = b.position[static_cast<size_t>(k)] - kDt * b.velocity[static_cast<size_t>(k)];
    }
  }
  return g;
}

// The positions velocityless Verlet predicts for the next step, with no force to add (world.cpp's
// step for this gas): x_{n+1} = 2x_n − x_{n−1}, into g.next (sized once: no allocation).
void predict(Gas& g) { g.next = 2 * g.x - g.previous; }
// And the step done once g.next has been projected.
void advance(Gas& g) {
  g.previous.swap(g.x);
  g.x.swap(g.next);
}

// The deepest overlap r_i + r_k − |x_k − x_i| over all N²/2 pairs (0 when none overlaps): the
// check that does not trust any broad phase.
double deepest_overlap(const Gas& g, const Vector& x) {
  double deepest = 0;
  const auto n = static_cast<Eigen::Index>(g.radius.size());
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index k = i + 1; k < n; ++k)
      deepest = std::max(deepest, g.radius[static_cast<size_t>(i)] + g.radius[static_cast<size_t>(k)] -
                                      (x.segment(g.d * k, g.d) - x.segment(g.d * i, g.d)).norm());
  return deepest;
}

motus::ConstraintProjection projection_of(const Gas& g, bool with_box, int iterations = 10) {
  return motus::ConstraintProjection(g.d, g.inverse_mass, g.radius, {}, {}, with_box ? g.box : motus::Colliders{},
                                     iterations);
}

TEST(BallPairs, AKeptListProjectsExactlyAsASearchFromScratch) {
  // A dense gas (gaps of 0.1 m to 0.5 m between balls of radii 0.3 to 0.5 m, up to 3 m/s) in its
  // box, stepped with one projection kept from step to step, and, at every step, the same
  // predicted positions projected by a projection made for that step alone (its candidates found
  // from scratch, as before the list was kept). Every pair within reach of a projection's start
  // is a candidate either way, in the same order: the positions agree to the last bit, and so
  // does the deepest overlap an all-pairs check finds.
  for (const int d : {2, 3}) {
    Gas g = lattice_gas(d, d == 2 ? 300 : 216, 1.1, 3, 0.4, true);
    motus::ConstraintProjection kept = projection_of(g, true);
    kept.project(g.x);
    double deepest = 0;
    for (int step = 0; step < 120; ++step) {
      predict(g);
      Vector fresh_x = g.next;
      kept.project(g.next);
      motus::ConstraintProjection fresh = projection_of(g, true);
      fresh.project(fresh_x);
      ASSERT_EQ(g.next, fresh_x) << d << "-D, step " << step;
      const double overlap = deepest_overlap(g, g.next);
      ASSERT_EQ(overlap, deepest_overlap(g, fresh_x)) << d << "-D, step " << step;
      deepest = std::max(deepest, overlap);
      advance(g);
    }
    std::printf("  %d-D gas of %zu balls, 120 steps: deepest overlap after a projection %.3g m\n", d, g.radius.size(),
                deepest);
    EXPECT_GT(deepest, 0);  // (there were contacts ten sweeps did not settle: the test compared something)
  }
}

TEST(BallPairs, TheListIsReusedAndAReuseLooksIntoNoBucket) {
  // ball_gas.json with verlet (400 balls of radius 0.5 m, 2 m apart, each velocity component up
  // to 1 m/s: at most 0.024 m a step), in its box, for 120 steps: the list is built far less
  // often than every step, and only a build looks into the hash. After the first projection has
  // sized everything, no step allocates, rebuilds included.
  Gas g = lattice_gas(2, 400, 2, 1);
  motus::ConstraintProjection p = projection_of(g, true);
  p.project(g.x);
  ASSERT_EQ(p.ball_pair_builds(), 1);
  const long queries_per_build = p.broad_phase_queries();
  EXPECT_GE(queries_per_build, 400);  // each ball looks into its own bucket at least
  EXPECT_LE(queries_per_build, 400 * 9);  // and into at most the 3² cells around it
  const long allocations = g_allocations.load();
  const int steps = 120;
  for (int step = 0; step < steps; ++step) {
    predict(g);
    p.project(g.next);
    advance(g);
  }
  EXPECT_EQ(g_allocations.load() - allocations, 0);
  const long builds = p.ball_pair_builds() - 1;
  std::printf("  ball gas of 400, %d steps: the list built %ld times, %ld bucket look-ups (%ld at the first build)\n",
              steps, builds, p.broad_phase_queries(), queries_per_build);
  EXPECT_GE(builds, 1);     // the balls did move (up to 2.8 m over the run)
  EXPECT_LT(builds, steps / 2);
  // Every build looks into about the same number of buckets (the lattice's balls in the same
  // number of cells, give or take those the gas moved across), and a reuse into none.
  EXPECT_LT(p.broad_phase_queries(), (builds + 1) * 2 * queries_per_build);

  // The same gas slowed to 1 mm/s moves at most √2 · 0.001 m/s · 2 s = 2.8 mm in 120 steps: no
  // sensible skin (any over 2.8 mm · 2, 1.2 % of a radius) needs a second build, and no bucket is
  // looked into again.
  Gas slow = lattice_gas(2, 400, 2, 0.001);
  motus::ConstraintProjection q = projection_of(slow, true);
  for (int step = 0; step < steps; ++step) {
    predict(slow);
    q.project(slow.next);
    advance(slow);
  }
  EXPECT_EQ(q.ball_pair_builds(), 1);
  EXPECT_EQ(q.broad_phase_queries(), queries_per_build);
}

TEST(BallPairs, ABallMovedFarIsFoundTheSameStep) {
  // A lattice of balls at rest (radius 0.5 m, 3 m apart), and ball 0 moved by hand 21 m, far
  // beyond any skin, to 0.1 m from ball 55's centre: the next projection sees that a ball moved,
  // builds the list again and separates the pair in the same projection, as a projection from
  // scratch does — to touching (one push of 0.45 m each, which reaches no other ball: a single
  // contact is exact after one push, like a single stick).
  Gas g = lattice_gas(2, 100, 3, 0);
  motus::ConstraintProjection p = projection_of(g, true);
  p.project(g.x);
  p.project(g.x);
  ASSERT_EQ(p.ball_pair_builds(), 1);  // nothing moved: no second build
  EXPECT_EQ(deepest_overlap(g, g.x), 0.0);
  g.x[0] = g.x[2 * 55] + 0.1;
  g.x[1] = g.x[2 * 55 + 1];
  Vector fresh_x = g.x;
  p.project(g.x);
  EXPECT_EQ(p.ball_pair_builds(), 2);
  motus::ConstraintProjection fresh = projection_of(g, true);
  fresh.project(fresh_x);
  EXPECT_EQ(g.x, fresh_x);
  EXPECT_LT(deepest_overlap(g, g.x), 1e-15);
  EXPECT_NEAR((g.x.segment(2 * 55, 2) - g.x.segment(0, 2)).norm(), 1.0, 1e-15);  // touching: r_0 + r_55
}

TEST(BallPairs, AFastBallThroughBallsAtRestIsCaughtAtEveryStep) {
  // The same lattice at rest, and ball 0 (a corner) thrown along the diagonal at 12 m/s, 0.2 m a
  // step — less than a skin's half at a time, so the list is reused between builds while the
  // ball crosses cells. Each step's projection agrees to the last bit with one from scratch (no
  // contact of the fast ball, or of the balls it knocks, is missed), the list is built again as
  // the fast ball goes, and not at every step (for any skin over 0.4 m, 0.8 radii, whose half is
  // more than a step).
  Gas g = lattice_gas(2, 100, 1.5, 0);
  g.previous[0] = g.x[0] - 0.2 / std::sqrt(2.0);
  g.previous[1] = g.x[1] - 0.2 / std::sqrt(2.0);
  motus::ConstraintProjection kept = projection_of(g, true);
  kept.project(g.x);
  const int steps = 60;
  double deepest = 0;
  for (int step = 0; step < steps; ++step) {
    predict(g);
    Vector fresh_x = g.next;
    kept.project(g.next);
    motus::ConstraintProjection fresh = projection_of(g, true);
    fresh.project(fresh_x);
    ASSERT_EQ(g.next, fresh_x) << "step " << step;
    deepest = std::max(deepest, deepest_overlap(g, g.next));
    advance(g);
  }
  EXPECT_GT(g.x.head(2).minCoeff(), 1.5);  // the fast ball did go into the lattice, pushing balls
  std::printf("  fast ball through 99 at rest, %d steps: %ld builds, deepest overlap %.3g m\n", steps,
              kept.ball_pair_builds(), deepest);
  EXPECT_GT(kept.ball_pair_builds(), 2);
  EXPECT_LT(kept.ball_pair_builds(), steps);
}

// The candidates found by looking at all N²/2 pairs: those closer than r_a + r_b + margin (margin:
// the largest radius), in (i, k) order.
std::vector<std::array<int, 2>> all_pairs_within_reach(const Gas& g, const Vector& x) {
  const int d = g.d;
  const auto n = static_cast<int>(g.radius.size());
  const double margin = *std::max_element(g.radius.begin(), g.radius.end());
  auto at = [&](int i) { return static_cast<size_t>(i); };
  std::vector<std::array<int, 2>> pairs;
  for (int i = 0; i < n; ++i)
    for (int k = i + 1; k < n; ++k) {
      double distance2 = 0;
      for (int c = 0; c < d; ++c) distance2 += (x[d * k + c] - x[d * i + c]) * (x[d * k + c] - x[d * i + c]);
      const double reach = g.radius[at(i)] + g.radius[at(k)] + margin;
      if (distance2 < reach * reach) pairs.push_back({i, k});
    }
  return pairs;
}

// One sweep of pushes over `pairs`, in their order: two overlapping balls move apart along the line
// of their centres until they touch, shared by inverse mass.
void push_pairs_apart(const Gas& g, const std::vector<std::array<int, 2>>& pairs, Vector& x) {
  const int d = g.d;
  auto at = [&](int i) { return static_cast<size_t>(i); };
  for (const auto& [i, k] : pairs) {
    const double wi = g.inverse_mass[i], wk = g.inverse_mass[k], w = wi + wk;
    double delta[3] = {0, 0, 0}, distance2 = 0;
    for (int c = 0; c < d; ++c) {
      delta[c] = x[d * k + c] - x[d * i + c];
      distance2 += delta[c] * delta[c];
    }
    const double touching = g.radius[at(i)] + g.radius[at(k)];
    if (distance2 >= touching * touching) continue;
    const double distance = std::sqrt(distance2);
    const double depth = (touching - distance) / distance;  // (no coincident centres in this gas)
    const double move_i = depth * wi / w, move_k = depth * wk / w;
    for (int c = 0; c < d; ++c) {
      x[d * i + c] -= move_i * delta[c];
      x[d * k + c] += move_k * delta[c];
    }
  }
}

// The projection of balls alone (no sticks, walls or pins) with its candidates from all N²/2
// pairs, then `sweeps` sweeps of pushes — constraint_projection.cpp's arithmetic, written out.
void all_pairs_projection(const Gas& g, Vector& x, int sweeps) {
  const auto pairs = all_pairs_within_reach(g, x);
  for (int sweep = 0; sweep < sweeps; ++sweep) push_pairs_apart(g, pairs, x);
}

TEST(BallPairs, PushesGoInTheOrderOfThePairsNotOfTheHash) {
  // The Gauss–Seidel pushes in (i, k) order, whatever the hash and whenever the list was built:
  // the dense gas of above, balls numbered at random, stepped by the projection (kept from step to
  // step, and by push_balls_apart, which shares its broad phase) and by the all-pairs projection
  // above, agrees to the last bit at every step.
  for (const int d : {2, 3}) {
    Gas g = lattice_gas(d, d == 2 ? 300 : 216, 1.1, 3, 0.4, true);
    Gas pushed = g;
    const int sweeps = 10;
    motus::ConstraintProjection p = projection_of(g, false, sweeps), q = projection_of(g, false, sweeps);
    Vector reference = g.x;
    p.project(g.x);
    q.push_balls_apart(pushed.x);
    all_pairs_projection(g, reference, sweeps);
    ASSERT_EQ(g.x, reference) << d << "-D, the start";
    ASSERT_EQ(pushed.x, reference) << d << "-D, the start";
    for (int step = 0; step < 60; ++step) {
      predict(g);
      predict(pushed);
      reference = g.next;
      p.project(g.next);
      q.push_balls_apart(pushed.next);
      all_pairs_projection(g, reference, sweeps);
      ASSERT_EQ(g.next, reference) << d << "-D, step " << step;
      ASSERT_EQ(pushed.next, reference) << d << "-D, step " << step;
      advance(g);
      advance(pushed);
    }
    EXPECT_LT(p.ball_pair_builds(), 60);  // (lists kept over steps were among those compared)
  }
}

// ---------------------------------------------------------------------------------
// The walls' broad phase: the sweeps' wall passes test only the bodies listed near each wall,
// lists kept across projections until a body has moved their skin; the projection's last wall
// pass tests every body (near_wall_lists.cpp, find_bodies_near_walls).

using Walls = std::vector<motus::ConstraintProjection::Wall>;

// n·x − offset − r for body i against every wall, the smallest: < 0 means inside one.
double lowest_height(const Walls& walls, const Vector& x, const std::vector<double>& radius, int d, int i) {
  double lowest = INFINITY;
  for (const auto& wall : walls) {
    double height = -wall.offset - radius[static_cast<size_t>(i)];
    for (int k = 0; k < d; ++k) height += wall.normal[static_cast<size_t>(k)] * x[d * i + k];
    lowest = std::min(lowest, height);
  }
  return lowest;
}

// The projection of balls in a box with no broad phase for the walls, as it was before the lists:
// candidates from all N²/2 pairs (those closer than r_a + r_b + the largest radius, in (i, k)
// order), then `sweeps` sweeps of every body against every wall followed by the pushes, then every
// body against every wall once more — constraint_projection.cpp's arithmetic, written out.
void every_wall_projection(const Gas& g, const Walls& walls, Vector& x, int sweeps) {
  const int d = g.d;
  const auto n = static_cast<int>(g.radius.size());
  auto at = [&](int i) { return static_cast<size_t>(i); };
  const auto pairs = all_pairs_within_reach(g, x);
  auto every_body_against_every_wall = [&] {
    for (const auto& wall : walls)
      for (int i = 0; i < n; ++i) {
        double height = -wall.offset - g.radius[at(i)];
        for (int c = 0; c < d; ++c) height += wall.normal[at(c)] * x[d * i + c];
        if (height < 0)
          for (int c = 0; c < d; ++c) x[d * i + c] -= height * wall.normal[at(c)];
      }
  };
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    every_body_against_every_wall();
    push_pairs_apart(g, pairs, x);
  }
  every_body_against_every_wall();
}

TEST(WallLists, AProjectionIsExactlyEveryBodyAgainstEveryWall) {
  // The dense gas of the ball pairs' tests (gaps of 0.1 m to 0.5 m, balls of radii 0.3 to 0.5 m,
  // up to 3 m/s, numbered at random) in its box, whose walls its outer balls start 0.55 m from:
  // stepped by one projection kept from step to step, and by the projection above that tests
  // every body against every wall in every pass. No ball crosses a margin (0.5 m) in one
  // projection, so no ball left off a list is ever inside a wall in a sweep: the positions agree
  // to the last bit at every step, lists kept over steps included.
  for (const int d : {2, 3}) {
    Gas g = lattice_gas(d, d == 2 ? 300 : 216, 1.1, 3, 0.4, true);
    motus::ConstraintProjection p = projection_of(g, true);
    const Walls walls = p.walls();
    const auto n = static_cast<int>(g.radius.size());
    Vector reference = g.x;
    p.project(g.x);
    every_wall_projection(g, walls, reference, 10);
    ASSERT_EQ(g.x, reference) << d << "-D, the start";
    int touches = 0;  // balls that ended a step on a wall
    for (int step = 0; step < 120; ++step) {
      predict(g);
      reference = g.next;
      p.project(g.next);
      every_wall_projection(g, walls, reference, 10);
      ASSERT_EQ(g.next, reference) << d << "-D, step " << step;
      for (int i = 0; i < n; ++i) touches += lowest_height(walls, g.next, g.radius, d, i) < 1e-12;
      advance(g);
    }
    const long every_body_every_sweep = 121L * 10 * static_cast<long>(walls.size()) * n;
    std::printf("  %d-D gas of %d balls in its box, 120 steps: %d touches of a wall, lists made %ld times, "
                "%ld body-wall tests in the sweeps (%.1f %% of every body in every sweep)\n",
                d, n, touches, p.near_wall_builds(), p.near_wall_tests(),
                100.0 * static_cast<double>(p.near_wall_tests()) / static_cast<double>(every_body_every_sweep));
    EXPECT_GT(touches, 100);  // the walls were hit: the comparison compared something
    EXPECT_LT(p.near_wall_tests(), every_body_every_sweep / 2);
  }
}

TEST(WallLists, TheSweepsTestTheBodiesNearTheWallsAndTheListsAreKept) {
  // ball_gas.json with verlet (400 balls of radius 0.5 m, 2 m apart in a 40 m box, each velocity
  // component up to 1 m/s: at most 0.024 m a step), 120 steps of 10 sweeps. The lists hold the
  // balls within margin + skin (0.5 m + 0.5 m) of a wall, the outer rows at most, so the sweeps
  // test a small part of the 400 × 4 body-wall pairs; they serve until a ball has moved 0.5 m,
  // about 21 steps at the fastest; no step allocates, new lists included.
  Gas g = lattice_gas(2, 400, 2, 1);
  motus::ConstraintProjection p = projection_of(g, true);
  p.project(g.x);
  ASSERT_EQ(p.near_wall_builds(), 1);
  const long allocations = g_allocations.load();
  const int steps = 120;
  for (int step = 0; step < steps; ++step) {
    predict(g);
    p.project(g.next);
    advance(g);
  }
  EXPECT_EQ(g_allocations.load() - allocations, 0);
  const long every_body_every_sweep = (steps + 1L) * 10 * 4 * 400;
  std::printf("  ball gas of 400, %d steps: the lists made %ld times, %ld body-wall tests in the sweeps (of %ld)\n",
              steps, p.near_wall_builds(), p.near_wall_tests(), every_body_every_sweep);
  EXPECT_GE(p.near_wall_builds(), 3);             // the balls did move
  EXPECT_LE(p.near_wall_builds(), steps / 10);    // and the lists were kept for many steps
  EXPECT_GT(p.near_wall_tests(), 0);              // the outer rows: 1 of 20 at the start
  EXPECT_LT(p.near_wall_tests(), every_body_every_sweep / 10);
}

TEST(WallLists, ASinglePlaneAndOneSweepNeedNoLists) {
  // A cloth's case (cloth.json: one floor, substeps of one sweep each): the sweep's own wall pass is
  // the projection's last, over every body, so there are no lists to make. With three sweeps the
  // first two use them, and the third is the pass over every body.
  motus::Colliders floor;
  floor.planes.push_back(ground());
  Vector x(4);
  x << 0, 0.5, 1, -0.25;
  motus::ConstraintProjection one(2, Vector::Ones(2), {0, 0}, {{0, 1, 1.0}}, {}, floor, 1);
  one.project(x);
  EXPECT_EQ(one.near_wall_builds(), 0);
  EXPECT_EQ(one.near_wall_tests(), 0);
  EXPECT_GE(x[3], 0.0);
  motus::ConstraintProjection three(2, Vector::Ones(2), {0, 0}, {{0, 1, 1.0}}, {}, floor, 3);
  three.project(x);
  EXPECT_EQ(three.near_wall_builds(), 1);
  EXPECT_EQ(three.near_wall_tests(), 2 * 2);  // both bodies within margin + skin (2 m) of the floor, two sweeps
  EXPECT_GE(x[1], 0.0);
  EXPECT_GE(x[3], 0.0);
}

TEST(WallLists, ABodyPulledFarIntoAWallWithinOneProjectionEndsOnItsSurface) {
  // Body 0 is pinned at (100, 5), far beyond the right wall of the box [0, 10]² (a pin wins over a
  // wall); body 1, free, is at the box's centre, 5 m from every wall, tied to body 0 by a stick of
  // 1 m stretched to 95 m. The margin is the longest stick, 1 m, and the skin as much: body 1 is on
  // no list, and the sweeps test no body at all. The first sweep's stick puts body 1 at (99, 5),
  // 89 m into the right wall, and so does each sweep after it; the last wall pass, over every body,
  // puts it on the wall's surface, x = 10 exactly (99 − 89).
  motus::Colliders box;
  box.boxes.push_back({{0, 0, 0}, {10, 10, 0}, 1});
  motus::ConstraintProjection p(2, Vector::Ones(2), {0, 0}, {{0, 1, 1.0}}, {{0, {100, 5, 0}}}, box, 4);
  Vector x(4);
  x << 100, 5, 5, 5;
  p.project(x);
  EXPECT_EQ(p.near_wall_builds(), 1);
  EXPECT_EQ(p.near_wall_tests(), 0);  // no body listed: the sweeps did not see it in the wall
  EXPECT_EQ(x[2], 10.0);              // but it did not end there
  EXPECT_EQ(x[3], 5.0);
  EXPECT_EQ(x[0], 100.0);  // the pin
  // The next projection lists it (now on the wall's surface), and the sweeps test it there.
  p.project(x);
  EXPECT_GT(p.near_wall_tests(), 0);
  EXPECT_EQ(x[2], 10.0);
}

TEST(WallLists, NoBodyEndsAStepInsideAWall) {
  // A heap: the dense gas (300 balls in 2-D, 216 in 3-D; radii 0.35 to 0.5 m, up to 3 m/s), its
  // balls paired into dumbbells, 2j with 2j + 1, by sticks of their start distance (1.1 m: the rows,
  // of 18 and 6 balls, are even, so no pair straddles two), falling under gravity onto its box's
  // floor for 240 steps (4 s).
  // After every step, every body against every wall, checked here: none is inside one by more
  // than rounding.
  for (const int d : {2, 3}) {
    Gas g = lattice_gas(d, d == 2 ? 300 : 216, 1.1, 3, 0.3, false);
    const auto n = static_cast<int>(g.radius.size());
    std::vector<motus::StickConstraint> sticks;
    for (int i = 0; i + 1 < n; i += 2)
      sticks.push_back({i, i + 1, (g.x.segment(d * (i + 1), d) - g.x.segment(d * i, d)).norm()});
    motus::ConstraintProjection p(d, g.inverse_mass, g.radius, sticks, {}, g.box, 10);
    const Walls walls = p.walls();
    p.project(g.x);
    double lowest = INFINITY;
    for (int step = 0; step < 240; ++step) {
      predict(g);
      for (int i = 0; i < n; ++i) g.next[d * i + 1] -= kG * kDt * kDt;
      p.project(g.next);
      for (int i = 0; i < n; ++i) {
        const double height = lowest_height(walls, g.next, g.radius, d, i);
        lowest = std::min(lowest, height);
        ASSERT_GE(height, -1e-12) << d << "-D, body " << i << ", step " << step;
      }
      advance(g);
    }
    const long every_body_every_sweep = 241L * 10 * static_cast<long>(walls.size()) * n;
    std::printf("  %d-D heap of %d balls in dumbbells, 240 steps: lowest height above a wall %.3g m, the lists made "
                "%ld times, %.1f %% of the body-wall tests of every body in every sweep\n",
                d, n, lowest, p.near_wall_builds(),
                100.0 * static_cast<double>(p.near_wall_tests()) / static_cast<double>(every_body_every_sweep));
    EXPECT_LT(lowest, 1e-12);  // the heap lies on the floor
    EXPECT_LT(p.near_wall_tests(), every_body_every_sweep);
  }
}

TEST(WallLists, ABodyPushedOutOfOneWallIntoAnotherIsAsBefore) {
  // A wedge of two planes: the floor y ≥ 0 and an overhanging wall x + y ≤ 1 (normal (−1, −1)/√2),
  // meeting at (1, 0) at 45°. A point 3 m deep in the floor at x = 1.5, 1.77 m from the overhang,
  // which it is not inside: pushed up out of the floor, it lands 0.35 m inside the overhang, whose
  // push sends it back down into the floor, and the sweeps take it towards the corner in turns.
  // Near the floor, whose push may send a body into the overhang, it is on the overhang's list too
  // and tested against both walls in every sweep, as before the lists: the same numbers as every
  // body against every wall, to the last bit. (Listed by its distance to each wall alone, it would
  // meet the overhang only in the last pass, and end there, 0.25 m inside the floor.)
  motus::Colliders wedge;
  wedge.planes.push_back(ground());
  wedge.planes.push_back({{-1, -1, 0}, -1, 1});  // −x − y ≥ −1
  Gas g;
  g.d = 2;
  g.x.resize(2);
  g.x << 1.5, -3;
  g.inverse_mass = Vector::Ones(1);
  g.radius = {0};
  motus::ConstraintProjection p(2, g.inverse_mass, g.radius, {}, {}, wedge, 10);
  Vector reference = g.x;
  p.project(g.x);
  every_wall_projection(g, p.walls(), reference, 10);
  EXPECT_EQ(g.x, reference);
  EXPECT_EQ(p.near_wall_tests(), 10 * 2);  // on both lists, in all ten sweeps
  EXPECT_NEAR(g.x[0], 1.0, 1e-3);  // near the corner, and all but out of both walls
  EXPECT_GT(lowest_height(p.walls(), g.x, g.radius, 2, 0), -1e-3);
}

TEST(WallLists, ATiltedFloorInABoxIsExactlyEveryBodyAgainstEveryWall) {
  // The dense gas of above in its box, over a floor tilted across it, y − 0.005·x ≥ −0.05: below
  // the box's own floor left of the middle, above it to the right, 0.049 m at the right wall (the
  // bottom row's balls clear it at the start). Its push has a part along −x, towards the left wall,
  // and it points against the ceiling: a body near it is on those walls' lists too. Planes and box
  // faces together, for 120 steps, the same numbers as every body against every wall.
  Gas g = lattice_gas(2, 300, 1.1, 3, 0.4, true);
  g.box.planes.push_back({{-0.005, 1, 0}, -0.05, 1});
  motus::ConstraintProjection p = projection_of(g, true);
  const Walls walls = p.walls();
  ASSERT_EQ(walls.size(), 5u);
  Vector reference = g.x;
  p.project(g.x);
  every_wall_projection(g, walls, reference, 10);
  ASSERT_EQ(g.x, reference) << "the start";
  int touches = 0;  // balls that ended a step on the tilted floor
  for (int step = 0; step < 120; ++step) {
    predict(g);
    reference = g.next;
    p.project(g.next);
    every_wall_projection(g, walls, reference, 10);
    ASSERT_EQ(g.next, reference) << "step " << step;
    for (size_t i = 0; i < g.radius.size(); ++i)
      touches += lowest_height({walls[0]}, g.next, g.radius, 2, static_cast<int>(i)) < 1e-12;
    advance(g);
  }
  std::printf("  gas of 300 over a tilted floor, 120 steps: %d touches of it\n", touches);
  EXPECT_GT(touches, 100);  // the tilted floor was hit
}

}  // namespace
