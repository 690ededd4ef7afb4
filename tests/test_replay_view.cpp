// The report's replay fits one view to every engine's frames (docs/cli.md, "The replay"), but not to
// an engine whose bodies went far from the first one's: a peer blown up to a thousand kilometres, still
// finite, shrank the others to a dot there, where `compare --render` had already left it out of its
// view (render/motus/render/shared_view.hpp: one rule for both).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "motus/compare/comparison.hpp"
#include "motus/compare/replay.hpp"

namespace {

using namespace motus;
using namespace motus::compare;

// One ball of radius 0.1 m, at rest at (0, 0), with no walls: the view is fitted to the frames.
SceneDescription one_ball() {
  SceneDescription scene;
  scene.name = "one_ball";
  MechanicalDescription m;
  m.dimensions = 2;
  BodyDescription body;
  body.radius = 0.1;
  body.position = {0.0, 0.0};
  body.velocity = {0.0, 0.0};
  m.bodies.push_back(body);
  scene.mechanical = m;
  return scene;
}

// An engine whose ball falls from (0, 0) to (0, y).
EngineRun falling_to(const char* engine, double y) {
  EngineRun run;
  run.engine = engine;
  for (const double at : {0.0, y}) run.frames.push_back(Snapshot{0, {0.0, at}, {0.0, 0.0}});
  return run;
}

}  // namespace

// The first engine reaches y = −2: its middle is y = −1 and its reach 1 (kFarthestInView = 4 reaches:
// down to y = −5). An engine that reached −4.9 is in the view; one at −1e6 (finite) is not, nor one with
// a NaN, and one that could not run has no frames to fit.
TEST(ReplayView, TakesInTheEnginesThatStayNearTheFirstOne) {
  const SceneDescription scene = one_ball();
  std::vector<EngineRun> runs = {falling_to("motus", -2), falling_to("box2d", -4.9), falling_to("bullet", -1e6),
                                 falling_to("plugin", std::nan("")), falling_to("other", -3)};
  runs[4].supported = false;
  runs[4].frames.clear();
  EXPECT_EQ(engines_in_view(scene, runs), (std::vector<bool>{true, true, false, false, false}));

  // The view: the two in view, each disc whole (radius 0.1 m): x from −0.1 to 0.1, y from −5.0 to 0.1.
  const ReplayView view = replay_view(scene, runs, engines_in_view(scene, runs));
  EXPECT_DOUBLE_EQ(view.x0, -0.1);
  EXPECT_DOUBLE_EQ(view.x1, 0.1);
  EXPECT_DOUBLE_EQ(view.y0, -4.9 - 0.1);
  EXPECT_DOUBLE_EQ(view.y1, 0.1);
}

// The panel of an engine left out says so, in its caption; the others' captions do not.
TEST(ReplayView, ThePanelOfAnEngineLeftOutSaysItsBodiesGoOutOfView) {
  const SceneDescription scene = one_ball();
  const std::vector<EngineRun> runs = {falling_to("motus", -2), falling_to("bullet", -1e6)};
  const std::string html = replay_section(scene, runs, engines_in_view(scene, runs));
  const auto bullet = html.find("<b>bullet</b>");
  ASSERT_NE(bullet, std::string::npos) << html;
  const auto outside = html.find("(goes out of view)");
  ASSERT_NE(outside, std::string::npos) << html;
  EXPECT_GT(outside, bullet);
  EXPECT_EQ(html.find("(goes out of view)", outside + 1), std::string::npos) << html;
}
