// A scene test: a scene run with the student's parts (its integrator, collision rules or projection),
// measured as motus measures it — velocities, energy, momentum, tunnelling, sticks, pins, bounces.
#include "motus/grade/checks/check_kinds.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include "motus/grade/checks/check_support.hpp"
#include "motus/integrate/integrator_catalog.hpp"
#include "motus/scene_error.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/mechanical_system.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

namespace {

// A body's numbers at a time, d of them each, body by body: "body 0 (1, 0), body 1 (0, 0)" (a
// newtons-cradle's 10 numbers in a row, "(1, 0, 0, 0, 0, 0, 0, 0, 0, 0)", left the reader to count
// out which ball had which). Numbers that are not whole bodies' are listed as they are.
std::string per_body(const std::vector<double>& xs, int d) {
  if (d < 1 || xs.empty() || xs.size() % static_cast<size_t>(d) != 0) return nums(xs);
  std::vector<std::string> bodies;
  for (size_t i = 0; i * static_cast<size_t>(d) < xs.size(); ++i) {
    std::vector<std::string> parts;
    for (size_t k = 0; k < static_cast<size_t>(d); ++k) parts.push_back(num(xs[i * static_cast<size_t>(d) + k]));
    bodies.push_back(fmt::format("body {} ({})", i, fmt::join(parts, ", ")));
  }
  return fmt::format("{}", fmt::join(bodies, ", "));
}

// A scene test's integrator: the scene's own unless given. motus's own runs only where the
// student's collision rules or constraint projection run in it — as motus's World decides
// (engine/motus/world.cpp): sticks and pins, and contacts under verlet, are projected; other
// contacts are resolved by the collision rules. Otherwise the test graded none of the student's
// code, and every submission passed it.
std::string scene_integrator(JsonFields& f, const SceneDescription& scene, const StudentParts& parts) {
  const bool given = f.has("integrator");
  const std::string name = f.string("integrator", scene.integrator);
  const auto builtin = integrator_from_name(name);
  if (!builtin) {
    const RunsStudent student = student_named_in(f, parts, name);
    check_runs_scene(f, student, scene, parts);
    return student.name;
  }
  // One the scene cannot run ("rk4 cannot run collisions") stopped every student's run.
  if (given) try {
      const Simulation can_run(scene, *builtin);
    } catch (const SceneError& e) {
      f.fail("integrator", e.what());
    }
  if (!parts.known) return name;
  const auto& m = *scene.mechanical;
  const long balls = std::count_if(m.bodies.begin(), m.bodies.end(), [](const auto& b) { return b.radius > 0; });
  const bool contacts = !m.colliders.empty() || balls >= 2, constrained = !m.sticks.empty() || !m.pins.empty();
  const bool projected = constrained || (contacts && *builtin == Integrator::Verlet);
  // (Short: one line is 400 characters, the file's path with it.)
  std::string why;
  if (projected && !parts.constraints)
    why = "under verlet, motus's projection resolves the scene's contacts and sticks; " + parts.file +
          " brings no projection";
  else if (!projected && contacts && !parts.collisions)
    why = "motus's collision rules resolve the scene's contacts; " + parts.file + " brings none";
  else if (!projected && !contacts)
    why = "the scene has no contacts, sticks or pins";
  if (!why.empty())
    f.fail("integrator",
           fmt::format("{} motus's and runs none of the student's code here ({}){}",
                       given ? "\"" + name + "\" is" : "missing (required): the scene's own, \"" + name + "\", is", why,
                       // (Only where one can run the scene: no student's integrator runs contacts or sticks.)
                       parts.integrators.empty() || contacts || constrained
                           ? ""
                           : "; name the student's integrator, " + choices(parts, true)));
  return name;
}

class SceneCheck final : public Check {
public:
  SceneCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts, std::string hint)
      : scene_(load_check_scene(f, test, source)), hint_(std::move(hint)) {
    if (!scene_.description.mechanical) throw SceneError(f.path_of("scene"), "a scene check needs a scene of bodies");
    request_.integrator = scene_integrator(f, scene_.description, parts);
    request_.dt = f.positive("dt", scene_.description.dt);
    const double duration = f.positive("duration", scene_.description.duration);
    request_.steps = f.integer("steps", fixed_step_count(duration, request_.dt));
    if (request_.steps < 1 || request_.steps > 10'000'000) f.fail("steps", "must be from 1 to 10,000,000");
    request_.every = f.integer("every", 1);
    if (request_.every < 1) f.fail("every", "must be ≥ 1");
    for (auto& m : f.objects("measure")) {
      Measure measure;
      measure.kind = m.string("kind");
      if (measure.kind == "final_velocities" || measure.kind == "final_positions") {
        // One number per body and dimension of the test's scene (its sets applied): a list of
        // another length failed every submission, the reference too ("Expected: (-2, 0, 0)").
        const auto& scene = *scene_.description.mechanical;
        const size_t bodies = scene.bodies.size(), d = static_cast<size_t>(scene.dimensions);
        measure.values = m.numbers("expect", -1);
        if (measure.values.size() != bodies * d)
          m.fail("expect", fmt::format("has {} number{}; the scene has {} bod{} in {}-D: {} numbers, body by body",
                                       measure.values.size(), measure.values.size() == 1 ? "" : "s", bodies,
                                       bodies == 1 ? "y" : "ies", d, bodies * d));
        measure.tolerance = m.positive("tolerance", 1e-9);
      } else if (measure.kind == "energy" || measure.kind == "momentum" || measure.kind == "stick_error") {
        // > 0, as every tolerance: these are measured in floating point, and rounding alone gives
        // about 1e-16 (a bound of 0 failed every submission, the reference's 1.58e-16 too).
        measure.tolerance = m.positive("max");
        measure.motus_times = m.non_negative("motus_times", 0);
      } else if (measure.kind == "pins" || measure.kind == "inside_walls" || measure.kind == "no_overlap") {
        measure.tolerance = m.non_negative("max");
        // The bound may instead be this many times what motus's own parts give on the same run
        // (measured in the same check), with `max` as the floor.
        measure.motus_times = m.non_negative("motus_times", 0);
      } else if (measure.kind == "bounce_ratio") {
        const long bodies = static_cast<long>(scene_.description.mechanical->bodies.size());
        const long body = m.integer("body", 0);
        if (body < 0 || body >= bodies)
          m.fail("body", "must name one of the scene's " + std::to_string(bodies) + " bodies, from 0 to " + std::to_string(bodies - 1));
        measure.body = static_cast<int>(body);
        if (scene_.description.mechanical->dimensions < 2) m.fail("kind", "bounce_ratio needs a scene in 2-D or 3-D (heights are y)");
        measure.expected = m.positive("expect");
        measure.tolerance = m.positive("tolerance", 1e-3);
        const long bounces = m.integer("bounces", 3);
        if (bounces < 1 || bounces > 1000) m.fail("bounces", "must be from 1 to 1,000");
        measure.bounces = static_cast<int>(bounces);
      } else {
        m.fail("kind",
               "must be final_velocities, final_positions, energy, momentum, stick_error, pins, inside_walls, "
               "no_overlap or bounce_ratio");
      }
      m.reject_unknown();
      measures_.push_back(measure);
    }
    if (measures_.empty()) f.fail("measure", "needs at least one measure");
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    const RunOutput out = grade::run(probe, scene_, request_, deadline);
    bool ok = true;
    std::string measured, expected;
    std::optional<RunOutput> motus;
    for (const auto& m0 : measures_) {
      Measure m = m0;
      std::string peer;
      if (m.motus_times > 0) {
        if (!motus) motus = motus_run();
        Measure plain = m;
        plain.tolerance = INFINITY;
        const double own = measured_value(plain, *motus);
        m.tolerance = std::max(m.tolerance, m.motus_times * own);
        peer = fmt::format(" ({} × motus's own {})", num(m.motus_times), num(own));
      }
      auto [good, got, want] = judge(m, out);
      want += peer;
      ok = ok && good;
      measured += (measured.empty() ? "" : "; ") + got;
      expected += (expected.empty() ? "" : "; ") + want;
    }
    return ok ? pass(measured) : fail(measured, expected, hint_);
  }

private:
  struct Measure {
    std::string kind;
    std::vector<double> values;
    double tolerance = 0, expected = 0;
    int body = 0, bounces = 3;
    double motus_times = 0;
  };

  // The same run with motus's own collision response and projection (the grader's, trusted).
  RunOutput motus_run() const {
    Simulation sim(scene_.description, scene_.description.integrator == request_.integrator
                                           ? Method(*integrator_from_name(request_.integrator))
                                           : Method(*integrator_from_name(scene_.description.integrator)));
    RunOutput out;
    auto row = [&](const Simulation& s) {
      out.t.push_back(s.time());
      out.y.push_back(s.state());
    };
    row(sim);
    sim.advance(sim.time() + static_cast<double>(request_.steps) * request_.dt, request_.dt, Tolerance{},
                [&](const Simulation& s) {
                  if (s.steps() % request_.every == 0) row(s);
                });
    out.steps = sim.steps();
    return out;
  }

  // The worst value over the run of a measure of the energy, momentum, sticks, pins, walls or overlaps.
  double measured_value(const Measure& m, const RunOutput& out) const {
    const auto& scene = *scene_.description.mechanical;
    const int d = scene.dimensions, n = static_cast<int>(scene.bodies.size());
    const Eigen::Index half = n * d;
    const MechanicalSystem system = measuring_system(scene_.description);
    double worst = 0;
    auto keep = [&](double value) { worst = std::isfinite(value) ? std::max(worst, value) : INFINITY; };
    if (m.kind == "energy") {
      const double e0 = energy(system, out.y.front());
      for (const auto& y : out.y) keep(std::abs(energy(system, y) - e0) / std::max(std::abs(e0), 1e-300));
    } else if (m.kind == "momentum") {
      double scale = 0;
      for (int i = 0; i < n; ++i) scale += scene.bodies[static_cast<size_t>(i)].mass * out.y.front().segment(half + i * d, d).norm();
      const Vector p0 = system.momentum(out.y.front().tail(half));
      for (const auto& y : out.y) keep((system.momentum(y.tail(half)) - p0).norm() / std::max(scale, 1e-300));
    } else if (m.kind == "stick_error") {
      for (const auto& y : out.y)
        for (const auto& s : scene.sticks) keep(std::abs((y.segment(s.a * d, d) - y.segment(s.b * d, d)).norm() - s.length) / s.length);
    } else if (m.kind == "pins") {
      for (const auto& y : out.y)
        for (const auto& p : scene.pins) {
          double distance = 0;
          for (int k = 0; k < d; ++k) distance += std::pow(y[p.body * d + k] - p.position[static_cast<size_t>(k)], 2);
          keep(std::sqrt(distance));
        }
    } else if (m.kind == "inside_walls") {
      // How far any body got into a wall (plane or box face), as a fraction of its radius (in m for a point).
      for (const auto& y : out.y)
        for (int i = 0; i < n; ++i) {
          const double r = scene.bodies[static_cast<size_t>(i)].radius;
          auto depth_into = [&](const double* normal, double offset) {
            double height = -offset - r;
            for (int k = 0; k < d; ++k) height += normal[k] * y[i * d + k];
            return -height / (r > 0 ? r : 1.0);  // (max(r, 1) read every ball under 1 m in metres)
          };
          for (const auto& p : scene.colliders.planes) {
            double length = 0;
            for (int k = 0; k < d; ++k) length += p.normal[static_cast<size_t>(k)] * p.normal[static_cast<size_t>(k)];
            length = std::sqrt(length);
            const double normal[3] = {p.normal[0] / length, p.normal[1] / length, p.normal[2] / length};
            keep(depth_into(normal, p.offset / length));
          }
          for (const auto& b : scene.colliders.boxes)
            for (int k = 0; k < d; ++k) {
              double low[3] = {0, 0, 0}, high[3] = {0, 0, 0};
              low[k] = 1;
              high[k] = -1;
              keep(depth_into(low, b.min[static_cast<size_t>(k)]));
              keep(depth_into(high, -b.max[static_cast<size_t>(k)]));
            }
          if (!y.segment(i * d, d).allFinite()) keep(INFINITY);
        }
    } else if (m.kind == "no_overlap") {
      for (const auto& y : out.y)
        for (int i = 0; i < n; ++i)
          for (int k = i + 1; k < n; ++k) {
            const double R = scene.bodies[static_cast<size_t>(i)].radius + scene.bodies[static_cast<size_t>(k)].radius;
            if (R > 0) keep((R - (y.segment(i * d, d) - y.segment(k * d, d)).norm()) / R);
          }
    }
    return worst;
  }

  std::tuple<bool, std::string, std::string> judge(const Measure& m, const RunOutput& out) const {
    const auto& scene = *scene_.description.mechanical;
    const int d = scene.dimensions, n = static_cast<int>(scene.bodies.size());
    const Eigen::Index half = n * d;
    const MechanicalSystem system = measuring_system(scene_.description);
    const Vector& last = out.y.back();
    if (m.kind == "final_velocities" || m.kind == "final_positions") {
      const bool velocities = m.kind == "final_velocities";
      const Vector got = velocities ? last.tail(half) : last.head(half);
      const bool good = all_close(to_std(got), m.values, m.tolerance);
      return {good,
              fmt::format("{} at t = {}: {}", velocities ? "velocities" : "positions", num(out.t.back()),
                          per_body(to_std(got), d)),
              fmt::format("{} (to {})", per_body(m.values, d), num(m.tolerance))};
    }
    if (m.kind == "energy" || m.kind == "momentum" || m.kind == "stick_error" || m.kind == "pins" ||
        m.kind == "inside_walls" || m.kind == "no_overlap") {
      const double worst = measured_value(m, out);
      static const std::map<std::string, std::pair<std::string, std::string>> words = {
          {"energy", {"largest |E − E₀|/|E₀| ", ""}},
          {"momentum", {"largest |p − p₀| / Σ m|v₀| ", ""}},
          {"stick_error", {"largest relative stick-length error ", ""}},
          {"pins", {"pinned bodies moved up to ", " m from their pins"}},
          {"inside_walls", {"the deepest any body got into a wall: ", " of its radius"}},
          {"no_overlap", {"the deepest overlap of two balls: ", " of their radii"}}};
      const auto& [before, after] = words.at(m.kind);
      return {worst <= m.tolerance, before + num(worst) + after,
              "at most " + num(m.tolerance) + after + (m.kind == "inside_walls" ? " (nothing tunnels)" : "")};
    }
    // bounce_ratio: the heights of successive tops of body m.body's flight above the ground
    // plane (the lowest upward plane), and their ratios.
    double ground = -INFINITY;
    for (const auto& p : scene.colliders.planes)
      if (p.normal[1] > 0.99) ground = std::max(ground, p.offset / p.normal[1]);
    const double r = scene.bodies[static_cast<size_t>(m.body)].radius;
    std::vector<double> tops;
    for (size_t k = 1; k + 1 < out.y.size(); ++k) {
      const double y0 = out.y[k - 1][m.body * d + 1], y1 = out.y[k][m.body * d + 1], y2 = out.y[k + 1][m.body * d + 1];
      if (y1 > y0 && y1 >= y2) tops.push_back(y1 - ground - r);
    }
    std::vector<double> ratios;
    bool good = tops.size() >= static_cast<size_t>(m.bounces) + 1;
    for (size_t k = 1; k < tops.size() && k <= static_cast<size_t>(m.bounces); ++k) {
      ratios.push_back(tops[k] / tops[k - 1]);
      good = good && std::abs(ratios.back() - m.expected) <= m.tolerance;
    }
    // Too few tops to measure a bounce: say how the flight went instead ("0 tops ... ()" said
    // nothing to a student whose ball sank into the floor and never rose again).
    if (tops.size() < 2) {
      double lowest = INFINITY;
      for (const auto& y : out.y) lowest = std::min(lowest, y[m.body * d + 1] - ground - r);
      return {false,
              fmt::format("{}; the lowest its surface got was {} m {} the ground",
                          tops.empty() ? "no top: the ball never rose again after it fell" : "one top: the ball rose once, never again",
                          num(std::abs(lowest)), lowest < 0 ? "below" : "above"),
              fmt::format("at least {} bounces, each top {} of the one before (to {})", m.bounces, num(m.expected),
                          num(m.tolerance))};
    }
    return {good, fmt::format("{} tops, each over the one before: {}", tops.size(), nums(ratios)),
            fmt::format("at least {} bounces, each top {} of the one before (to {})", m.bounces, num(m.expected),
                        num(m.tolerance))};
  }

  CheckScene scene_;
  RunRequest request_;
  std::vector<Measure> measures_;
  std::string hint_;
};

}  // namespace

std::unique_ptr<Check> detail::make_scene_check(JsonFields& f, const json& test, const SceneSource& source,
                                                const StudentParts& parts, const std::string& hint) {
  return std::make_unique<SceneCheck>(f, test, source, parts, hint);
}

}  // namespace motus::grade
