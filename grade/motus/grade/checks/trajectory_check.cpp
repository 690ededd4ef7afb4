// A trajectory test: the student's integrator runs the test's scene, and its states at given steps
// are compared with the test's own numbers.
#include "motus/grade/checks/check_kinds.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "motus/grade/checks/check_support.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

namespace {

class TrajectoryCheck final : public Check {
public:
  TrajectoryCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts, std::string hint)
      : scene_(load_check_scene(f, test, source)), hint_(std::move(hint)) {
    const RunsStudent integrator = student_integrator(f, parts, "a trajectory test");
    check_runs_scene(f, integrator, scene_.description, parts);
    request_.integrator = integrator.name;
    request_.dt = f.positive("dt", scene_.description.dt);
    tolerance_ = f.positive("tolerance", 1e-9);
    // The state's size: x and v are half of it each, y all of it (a row of another size could only fail).
    const auto& m = scene_.description.mechanical;
    const int half = m ? m->dimensions * static_cast<int>(m->bodies.size()) : -1;
    const int whole = m ? 2 * half : static_cast<int>(scene_.description.first_order->initial.size());
    for (auto& e : f.objects("expect")) {
      Row row;
      row.step = e.integer("step");
      if (row.step < 0 || row.step > 10'000'000) e.fail("step", "must be from 0 to 10,000,000");
      for (const char* key : {"x", "v"})
        if (!m && e.has(key)) e.fail(key, "the scene has no bodies: its state is y");
      if (e.has("x")) row.x = e.numbers("x", half);
      if (e.has("v")) row.v = e.numbers("v", half);
      if (e.has("y")) row.y = e.numbers("y", whole);
      if (row.x.empty() && row.v.empty() && row.y.empty()) e.fail("", "needs x, v or y");
      e.reject_unknown();
      request_.steps = std::max(request_.steps, row.step);
      rows_.push_back(row);
    }
    if (rows_.empty()) f.fail("expect", "needs at least one row");
    request_.steps = std::max(1L, request_.steps);
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    const RunOutput out = grade::run(probe, scene_, request_, deadline);
    std::string measured, expected;
    bool ok = true;
    for (const auto& row : rows_) {
      if (row.step >= static_cast<long>(out.y.size())) throw ProbeFailure("the run stopped before step " + std::to_string(row.step));
      const Vector& y = out.y[static_cast<size_t>(row.step)];
      const Eigen::Index half = y.size() / 2;
      std::string m = "at t = " + num(out.t[static_cast<size_t>(row.step)]) + ":", e = m;
      auto compare = [&](const char* name, const std::vector<double>& want, const Vector& got) {
        if (want.empty()) return;
        ok = ok && all_close(to_std(got), want, tolerance_);
        m += fmt::format(" {} = {}", name, nums(to_std(got)));
        e += fmt::format(" {} = {}", name, nums(want));
      };
      compare("x", row.x, y.head(half));
      compare("v", row.v, y.tail(half));
      compare("y", row.y, y);
      measured += (measured.empty() ? "" : "; ") + m;
      expected += (expected.empty() ? "" : "; ") + e;
    }
    expected += fmt::format(" (each to {} relative)", num(tolerance_));
    return ok ? pass(measured) : fail(measured, expected, hint_);
  }

private:
  struct Row {
    long step = 0;
    std::vector<double> x, v, y;
  };
  CheckScene scene_;
  RunRequest request_;
  std::vector<Row> rows_;
  double tolerance_ = 1e-9;
  std::string hint_;
};

}  // namespace

std::unique_ptr<Check> detail::make_trajectory_check(JsonFields& f, const json& test, const SceneSource& source,
                                                     const StudentParts& parts, const std::string& hint) {
  return std::make_unique<TrajectoryCheck>(f, test, source, parts, hint);
}

}  // namespace motus::grade
