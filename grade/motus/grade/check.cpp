// make_check: a test's kind to its check, one kind a file under checks/ (checks/check_kinds.hpp).
#include "motus/grade/check.hpp"

#include <fmt/format.h>

#include <map>

#include "motus/grade/checks/check_kinds.hpp"
#include "motus/grade/checks/check_support.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

std::unique_ptr<Check> make_check(JsonFields& test, const SceneSource& scenes, const StudentParts& parts,
                                  const std::string& hint) {
  const std::string kind = test.string("kind");
  const json& raw = test.raw();
  // (Before the kind's own fields: an order test's scene without an exact solution is no matter
  // in an assignment whose plug-in brings no integrator to measure.)
  static const std::map<std::string, std::string> of_integrators = {
      {"trajectory", "a trajectory test"}, {"order", "an order test"},       {"stability", "a stability test"},
      {"energy", "an energy test"},         {"adaptive", "an adaptive test"}, {"step", "a step test"}};
  if (const auto it = of_integrators.find(kind); it != of_integrators.end() && parts.known && parts.integrators.empty())
    test.fail("kind", fmt::format("{} grades the student's integrator, and the assignment's plug-in ({}) brings none (it "
                                  "brings {})",
                                  it->second, parts.file, brings(parts)));
  if (kind == "trajectory") return make_trajectory_check(test, raw, scenes, parts, hint);
  if (kind == "order") return make_order_check(test, raw, scenes, parts, hint);
  if (kind == "stability") return make_stability_check(test, raw, scenes, parts, hint);
  if (kind == "energy") return make_energy_check(test, raw, scenes, parts, hint);
  if (kind == "adaptive") return make_adaptive_check(test, raw, scenes, parts);
  if (kind == "call") return make_call_check(test, raw, parts, hint);
  if (kind == "scene") return make_scene_check(test, raw, scenes, parts, hint);
  if (kind == "project") return make_project_check(test, raw, parts, hint);
  if (kind == "step") return make_step_check(test, raw, parts, hint);
  test.fail("kind", "must be trajectory, order, stability, energy, adaptive, call, scene, project or step");
}

}  // namespace motus::grade
