// A project test: the student's constraint projection called on the test's positions, sticks, pins
// and walls, its result against the test's bounds.
#include "motus/grade/checks/check_kinds.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "motus/grade/checks/check_support.hpp"
#include "motus/grade/wire.hpp"
#include "motus/scene_error.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

namespace {

// ---- Fields read by hand ----------------------------------------------------------------------------

// `key`: an array (none: empty) of arrays of `size` items each, such as a project test's sticks.
json read_rows(const JsonFields& f, const json& test, const std::string& key, size_t size) {
  const json rows = test.value(key, json::array());
  if (!rows.is_array()) throw SceneError(f.path_of(key), "must be an array, not " + json_type_name(rows));
  for (size_t k = 0; k < rows.size(); ++k)
    if (!rows[k].is_array() || rows[k].size() != size)
      throw SceneError(f.path_of(key) + "[" + std::to_string(k) + "]",
                       "must be an array of " + std::to_string(size) + " items, not " +
                           (rows[k].is_array() ? std::to_string(rows[k].size()) + " items" : json_type_name(rows[k])));
  return rows;
}

double finite_number(const json& value, const std::string& path) {
  if (!value.is_number() || !std::isfinite(value.get<double>()))
    throw SceneError(path, "must be a finite number, not " + json_type_name(value));
  return value.get<double>();
}

// A body's number, one of the test's n bodies.
int body_number(const json& value, int n, const std::string& path) {
  if (!value.is_number_integer() || value.get<long>() < 0 || value.get<long>() >= n)
    throw SceneError(path, "must name one of the test's " + std::to_string(n) + " bodies, a whole number from 0 to " +
                               std::to_string(n - 1) + ", not " + value.dump());
  return value.get<int>();
}

// A point (or a direction) of d finite numbers.
std::vector<double> point(const json& value, int d, const std::string& path) {
  if (!value.is_array() || value.size() != static_cast<size_t>(d))
    throw SceneError(path, "must be an array of " + std::to_string(d) + " numbers (the test's dimensions), not " + value.dump());
  std::vector<double> out;
  for (size_t k = 0; k < value.size(); ++k) out.push_back(finite_number(value[k], path + "[" + std::to_string(k) + "]"));
  return out;
}

class ProjectCheck final : public Check {
public:
  ProjectCheck(JsonFields& f, const json& test, const StudentParts& parts, std::string hint) : hint_(std::move(hint)) {
    if (parts.known && !parts.constraints)
      f.fail("kind", fmt::format("a project test calls the student's constraint projection, and the assignment's plug-in "
                                 "({}) brings none (it brings {})",
                                 parts.file, brings(parts)));
    for (const char* key : {"sticks", "pins", "walls"}) f.use(key);  // read by hand below
    d_ = static_cast<int>(f.integer("dimensions"));
    if (d_ < 1 || d_ > 3) f.fail("dimensions", "must be 1, 2 or 3");
    x_ = f.numbers("x", -1);
    inverse_mass_ = f.numbers("inverse_mass", -1);
    const int n = static_cast<int>(inverse_mass_.size());
    if (static_cast<int>(x_.size()) != n * d_) f.fail("x", "needs dimensions × bodies numbers");
    radius_ = f.numbers("radius", n, std::vector<double>(static_cast<size_t>(n), 0.0));
    iterations_ = static_cast<int>(f.integer("iterations", 1));
    if (iterations_ < 1 || iterations_ > 1'000'000) f.fail("iterations", "must be from 1 to 1,000,000");
    // Each stick, pin and wall is checked here, when the tests are read: a slip in them is the
    // instructor's one-line error, not every student's failed test ("your code stopped the run").
    const json sticks = read_rows(f, test, "sticks", 3), pins = read_rows(f, test, "pins", 2),
               walls = read_rows(f, test, "walls", 2);
    for (size_t k = 0; k < sticks.size(); ++k) {
      const std::string at = f.path_of("sticks") + "[" + std::to_string(k) + "]";
      const Stick s{body_number(sticks[k][0], n, at + "[0]"), body_number(sticks[k][1], n, at + "[1]"),
                    finite_number(sticks[k][2], at + "[2]")};
      if (s.a == s.b) throw SceneError(at, "joins body " + std::to_string(s.a) + " to itself");
      if (!(s.length > 0)) throw SceneError(at + "[2]", "a stick's length must be > 0");
      sticks_.push_back(s);
    }
    for (size_t k = 0; k < pins.size(); ++k) {
      const std::string at = f.path_of("pins") + "[" + std::to_string(k) + "]";
      pins_.push_back({body_number(pins[k][0], n, at + "[0]"), point(pins[k][1], d_, at + "[1]")});
    }
    for (size_t k = 0; k < walls.size(); ++k) {
      const std::string at = f.path_of("walls") + "[" + std::to_string(k) + "]";
      const std::vector<double> normal = point(walls[k][0], d_, at + "[0]");
      if (std::all_of(normal.begin(), normal.end(), [](double c) { return c == 0; }))
        throw SceneError(at + "[0]", "a wall's normal must not be zero");
      finite_number(walls[k][1], at + "[1]");
    }
    request_ = {{"op", "project"}, {"dimensions", d_}, {"x", x_}, {"inverse_mass", inverse_mass_}, {"radius", radius_},
                {"sticks", sticks}, {"pins", pins}, {"walls", walls}, {"iterations", iterations_}};
    auto e = f.object("expect");
    if (e.has("x")) expect_x_ = e.numbers("x", n * d_);
    if (e.has("stick_error")) stick_error_ = e.non_negative("stick_error");
    if (e.has("pins")) pins_max_ = e.non_negative("pins");
    if (e.has("centre_of_mass")) centre_max_ = e.non_negative("centre_of_mass");
    tolerance_ = e.positive("tolerance", 1e-9);
    e.reject_unknown();
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    const json reply = probe.ask(request_, deadline, ReplySize{x_.size() + 256});
    const auto x_at = reply.find("x");
    if (x_at == reply.end() || !x_at->is_array() || !std::all_of(x_at->begin(), x_at->end(), is_wire_number))
      malformed_reply("the reply of satisfy_constraints", "its \"x\" is not an array of numbers");
    const std::vector<double> x = wire::numbers(*x_at);
    if (x.size() != x_.size()) throw ProbeFailure("the projection returned " + std::to_string(x.size()) + " numbers");
    bool ok = true;
    std::string measured, expected;
    auto add = [&](bool good, const std::string& m, const std::string& e) {
      ok = ok && good;
      measured += (measured.empty() ? "" : "; ") + m;
      expected += (expected.empty() ? "" : "; ") + e;
    };
    auto at = [&](const std::vector<double>& p, int i) {
      return Eigen::Map<const Vector>(p.data() + i * d_, d_);
    };
    if (!expect_x_.empty())
      add(all_close(x, expect_x_, tolerance_), "positions " + nums(x), "positions " + nums(expect_x_));
    if (!std::isnan(stick_error_)) {
      double worst = 0;
      for (const auto& s : sticks_) worst = std::max(worst, std::abs((at(x, s.a) - at(x, s.b)).norm() - s.length) / s.length);
      if (!std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })) worst = INFINITY;
      add(worst <= stick_error_, "largest relative stick-length error " + num(worst), "at most " + num(stick_error_));
    }
    if (!std::isnan(pins_max_)) {
      double worst = 0;
      for (const auto& p : pins_) worst = std::max(worst, (at(x, p.body) - Eigen::Map<const Vector>(p.position.data(), d_)).norm());
      // (std::max keeps 0 against a NaN distance: positions that are not numbers are off their pins.)
      if (!std::all_of(x.begin(), x.end(), [](double v) { return std::isfinite(v); })) worst = INFINITY;
      add(worst <= pins_max_, "pinned bodies off their pins by up to " + num(worst) + " m", "at most " + num(pins_max_) + " m");
    }
    if (!std::isnan(centre_max_)) {
      // Σ x_i / w_i: the centre of mass, which sticks between free bodies must not move.
      Vector before = Vector::Zero(d_), after = Vector::Zero(d_);
      double mass = 0;
      for (size_t i = 0; i < inverse_mass_.size(); ++i) {
        const double m = 1 / inverse_mass_[i];
        before += m * at(x_, static_cast<int>(i));
        after += m * at(x, static_cast<int>(i));
        mass += m;
      }
      const double moved = ((after - before) / mass).norm();
      add(moved <= centre_max_, "the centre of mass moved " + num(moved) + " m", "at most " + num(centre_max_) + " m");
    }
    return ok ? pass(measured) : fail(measured, expected, hint_);
  }

private:
  struct Stick {
    int a, b;
    double length;
  };
  struct Pin {
    int body;
    std::vector<double> position;
  };
  int d_ = 2, iterations_ = 1;
  std::vector<double> x_, inverse_mass_, radius_, expect_x_;
  std::vector<Stick> sticks_;
  std::vector<Pin> pins_;
  double stick_error_ = NAN, pins_max_ = NAN, centre_max_ = NAN, tolerance_ = 1e-9;
  json request_;
  std::string hint_;
};

}  // namespace

std::unique_ptr<Check> detail::make_project_check(JsonFields& f, const json& test, const StudentParts& parts, const std::string& hint) {
  return std::make_unique<ProjectCheck>(f, test, parts, hint);
}

}  // namespace motus::grade
