// "exact": "free-flight" (engine/motus/exact/free_flight.hpp): the event-by-event answer of a
// collision scene, checked against the closed forms it must reproduce — the 1-D elastic
// collision formulas, the 90° exit of equal smooth balls, the cradle, bounce heights h·e^(2k),
// the parabola — and against the loader's refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "motus/exact/exact_solution.hpp"
#include "motus/scene_error.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace {

using motus::SceneDescription;

SceneDescription load(const std::string& name) { return motus::load_scene(MOTUS_SCENES_DIR "/" + name + ".json"); }

motus::Vector state_at(const SceneDescription& s, double t) {
  const auto y = motus::exact_state(s, t);
  EXPECT_TRUE(y.has_value()) << "no exact state at t = " << t;
  return y.value_or(motus::Vector::Zero(static_cast<Eigen::Index>(4 * s.mechanical->bodies.size())));
}

TEST(FreeFlight, HeadOnGivesTheOneDimensionalElasticFormulas) {
  const auto s = load("head_on");  // m = 1 at x = −2 moving +1, m = 3 at x = 2 moving −1, r = 0.5
  const double m1 = 1, m2 = 3, u1 = 1, u2 = -1;
  const double v1 = ((m1 - m2) * u1 + 2 * m2 * u2) / (m1 + m2), v2 = ((m2 - m1) * u2 + 2 * m1 * u1) / (m1 + m2);
  // Contact when the 3 m gap closes at 2 m/s: t = 1.5 s, at x = −0.5 and 0.5.
  const double T = 4, contact = 1.5;
  const auto y = state_at(s, T);  // [x1 y1 x2 y2 | v...]
  EXPECT_NEAR(y[4], v1, 1e-14);
  EXPECT_NEAR(y[6], v2, 1e-14);
  EXPECT_NEAR(y[0], -0.5 + v1 * (T - contact), 1e-13);
  EXPECT_NEAR(y[2], 0.5 + v2 * (T - contact), 1e-13);
  // Before the contact, straight lines.
  const auto before = state_at(s, 1.0);
  EXPECT_DOUBLE_EQ(before[0], -1.0);
  EXPECT_DOUBLE_EQ(before[2], 1.0);
}

TEST(FreeFlight, ObliqueHitSendsEqualSmoothBallsOffAtRightAngles) {
  const auto s = load("oblique");  // 1 m/s, impact parameter 0.5 with contact distance 1: 30° off centre
  const auto y = state_at(s, 4);
  const double a[2] = {y[4], y[5]}, b[2] = {y[6], y[7]};
  EXPECT_NEAR(a[0] * b[0] + a[1] * b[1], 0, 1e-14);                      // at right angles
  EXPECT_NEAR(a[0] * a[0] + a[1] * a[1] + b[0] * b[0] + b[1] * b[1], 1, 1e-14);  // e = 1
  const double angle = std::asin(0.5 / 1.0);  // between the velocity and the line of centres
  EXPECT_NEAR(b[0], std::cos(angle) * std::cos(angle), 1e-14);  // the struck ball: along the line of centres
  EXPECT_NEAR(b[1], -std::cos(angle) * std::sin(angle), 1e-14);
}

TEST(FreeFlight, NewtonsCradleHandsTheWholeSpeedToTheLastBall) {
  const auto s = load("newtons_cradle");  // a ball at 1 m/s meets four at rest in contact, at t = 1 s
  const auto y = state_at(s, 3);
  const int n = 5;
  for (int i = 0; i < n - 1; ++i) EXPECT_NEAR(y[2 * n + 2 * i], 0, 1e-15) << "ball " << i;
  EXPECT_NEAR(y[2 * n + 2 * (n - 1)], 1, 1e-15);
  EXPECT_NEAR(y[2 * (n - 1)], 4 + (3 - 1), 1e-13);  // the last leaves x = 4 at t = 1
  EXPECT_NEAR(y[0], 0, 1e-13);                      // the first stopped where it struck
}

TEST(FreeFlight, DropBouncesToHeightTimesRestitutionSquaredAndThenRests) {
  const auto s = load("drop");  // centre at 10.5 m, radius 0.5, e = 0.8, g = 9.81
  const double g = 9.81, e = 0.8, h = 10, radius = 0.5;
  const double fall = std::sqrt(2 * h / g), impact = g * fall;
  double t = fall, speed = impact;
  for (int k = 1; k <= 3; ++k) {  // the k-th apex: h e^(2k) above the ground, speed e^k · impact upward at the bounce
    speed *= e;
    const double apex = t + speed / g;
    const auto y = state_at(s, apex);
    EXPECT_NEAR(y[1] - radius, h * std::pow(e, 2 * k), 1e-11) << "apex " << k;
    EXPECT_NEAR(y[3], 0, 1e-12);
    t += 2 * speed / g;
  }
  // The bounces accumulate at t = fall (1 + 2e/(1 − e)): after that the solution says nothing.
  const double rest = fall * (1 + 2 * e / (1 - e));
  EXPECT_TRUE(motus::exact_state(s, rest - 0.05).has_value());
  EXPECT_FALSE(motus::exact_state(s, rest + 0.05).has_value());
}

// A ball set down on the floor, touching it at rest: gravity holds it there, and the exact
// answer does not know how long it stays (it is at rest on a wall: unknown from then on). It let
// the ball fall through the floor, ½ g t² below (314 m at t = 8 s), and compare blamed all three
// engines for holding it up. (From an audit.)
TEST(FreeFlight, ABallSetDownOnTheFloorIsAtRestNotFallingThroughIt) {
  auto s = load("drop");
  s.mechanical->bodies[0].position[1] = 0.5;  // its radius: touching the floor
  EXPECT_FALSE(motus::exact_state(s, 8).has_value());
  s.mechanical->bodies[0].position[1] = 0.5000001;  // a hair above: it falls that hair, bounces, and rests
  EXPECT_TRUE(motus::exact_state(s, 1e-4).has_value());
}

TEST(FreeFlight, FreeFallIsTheParabola) {
  const auto s = load("free_fall");
  for (double t : {0.0, 0.7, 2.0}) {
    const auto y = state_at(s, t);
    EXPECT_NEAR(y[0], 3 * t, 1e-13);
    EXPECT_NEAR(y[1], 10 * t - 0.5 * 9.81 * t * t, 1e-13);
    EXPECT_NEAR(y[3], 10 - 9.81 * t, 1e-13);
  }
}

TEST(FreeFlight, BallBetweenTwoWallsOfABoxHasThePeriodOfItsRoundTrip) {
  // 1-D, no gravity: a ball of radius 0.5 at 2 m/s in a box [0, 10] travels 9 m each way.
  const auto s = motus::parse_scene(R"({"name": "shuttle", "dimensions": 1,
    "bodies": [{"mass": 1, "radius": 0.5, "position": [5], "velocity": [2]}],
    "colliders": [{"type": "box", "min": [0], "max": [10]}], "dt": 0.01, "duration": 20, "exact": "free-flight"})",
                                     "shuttle.json");
  const double period = 2 * 9 / 2.0;
  const auto start = state_at(s, 0), later = state_at(s, 2 * period);
  EXPECT_NEAR(later[0], start[0], 1e-12);
  EXPECT_NEAR(later[1], 2, 1e-15);
  EXPECT_NEAR(state_at(s, 2.25)[0], 9.5, 1e-12);  // at the far wall
}

TEST(FreeFlight, RefusesWhatItDoesNotSolve) {
  auto refuses = [](const std::string& json, const std::string& words) {
    try {
      motus::parse_scene(json, "bad.json");
      ADD_FAILURE() << "accepted: " << json;
    } catch (const std::exception& e) {
      EXPECT_NE(std::string(e.what()).find("exact"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  const std::string head = R"({"name": "x", "dimensions": 2, "dt": 0.01, "duration": 1, "exact": "free-flight", )";
  refuses(head + R"("bodies": [{"mass": 1, "radius": 0.5, "position": [0, 0]}, {"mass": 1, "radius": 0.5, "position": [0.5, 0]}]})",
          "overlap");
  refuses(head + R"("bodies": [{"mass": 1, "radius": 0.5, "position": [0, 0]}], "forces": [{"type": "drag", "coefficient": 1}]})",
          "uniform gravity");
  refuses(head + R"("bodies": [{"mass": 1, "radius": 0.5, "position": [0, 0]}],
          "colliders": [{"type": "segment", "a": [-1, -1], "b": [1, -1]}]})",
          "segments");
  refuses(head + R"("bodies": [{"mass": 1, "radius": 0.5, "position": [0, 0.2]}],
          "colliders": [{"type": "plane", "normal": [0, 1], "offset": 0}]})",
          "inside");
}

}  // namespace
