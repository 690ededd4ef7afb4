#include "motus/grade/check.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <ranges>
#include <sstream>

#include "motus/exact/exact_solution.hpp"
#include "motus/integrator_name.hpp"
#include "motus/grade/wire.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/scene_file/scene_overrides.hpp"
#include "motus/scene_file/spelling.hpp"
#include "motus/scene_error.hpp"
#include "motus/simulation.hpp"
#include "motus/systems/mechanical_system.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace motus::grade {
namespace {

using Clock = std::chrono::steady_clock;

// ---- Words and numbers for the messages -------------------------------------------------------

std::string num(double x) {
  if (std::isnan(x)) return "NaN";
  if (std::isinf(x)) return x > 0 ? "∞" : "−∞";
  return fmt::format("{:.6g}", x);
}

std::string nums(const std::vector<double>& xs) {
  std::vector<std::string> parts;
  for (double x : xs) parts.push_back(num(x));
  if (xs.size() == 1) return parts.front();
  return fmt::format("({})", fmt::join(parts, ", "));  // (one format: GCC 12 warns falsely on "(" + string, PR105651)
}

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

CheckResult pass(std::string measured) { return {true, "Measured: " + measured + "."}; }

CheckResult fail(const std::string& measured, const std::string& expected, const std::string& hint) {
  std::string out = "Measured: " + measured + ".\nExpected: " + expected + ".";
  if (!hint.empty()) out += "\nThis usually means: " + hint;
  return {false, out};
}

// |a − b| within tolerance, scaled by the size of what was expected (at least 1).
bool close(double measured, double expected, double tolerance) {
  if (std::isinf(expected)) return measured == expected;
  return std::abs(measured - expected) <= tolerance * std::max(1.0, std::abs(expected));
}

bool all_close(const std::vector<double>& measured, const std::vector<double>& expected, double tolerance) {
  if (measured.size() != expected.size()) return false;
  for (size_t i = 0; i < measured.size(); ++i)
    if (!close(measured[i], expected[i], tolerance)) return false;
  return true;
}

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

// ---- Scenes and runs ------------------------------------------------------------------------------

std::string read_text(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw SceneError(file, "cannot be read");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// "set": ["dt=1", ...], read by hand: JsonFields has no array-of-strings reader.
std::vector<std::string> read_sets(const json& test, const std::string& path) {
  std::vector<std::string> sets;
  if (!test.contains("set")) return sets;
  const json& s = test.at("set");
  if (!s.is_array()) throw SceneError(path + ".set", "must be an array of \"PATH=VALUE\" strings");
  for (size_t i = 0; i < s.size(); ++i) {
    if (!s[i].is_string()) throw SceneError(path + ".set[" + std::to_string(i) + "]", "must be a string PATH=VALUE");
    sets.push_back(s[i].get<std::string>());
  }
  return sets;
}

CheckScene load_check_scene(JsonFields& f, const json& test, const SceneSource& source) {
  CheckScene scene;
  if (f.has("scene_file")) {
    // Inside the tests' own folder: the autograder's zip takes that folder (and the assignment's)
    // and nothing beside it, so a scene reached by ../ or from / would be missing there.
    const fs::path relative = fs::path(f.string("scene_file")).lexically_normal();
    if (relative.empty() || relative.is_absolute() || *relative.begin() == "..")
      f.fail("scene_file", "\"" + f.string("scene_file") +
                               "\" must be a path inside the tests' folder (the autograder's zip holds nothing beside it)");
    scene.file = (fs::path(source.tests_folder) / relative).string();
    if (!fs::is_regular_file(scene.file)) f.fail("scene_file", scene.file + ": no such file");
  } else {
    scene.file = source.shipped(f.string("scene"));
    // (Named as the test's field: "tests/public.json: sprnig: cannot be read" named neither.)
    if (!fs::is_regular_file(scene.file))
      f.fail("scene", "\"" + f.string("scene") + "\" is no shipped scene" +
                          (source.guess ? source.guess(f.string("scene")) : std::string()) +
                          " (motus list shows them; a file of the tests' own is a scene_file)");
  }
  f.use("set");  // read by hand below
  const std::vector<std::string> sets = read_sets(test, f.path());
  const std::string text = read_text(scene.file);
  scene.description = parse_scene(text, scene.file, sets);
  scene.text = scene_for_the_sandbox(text, sets);
  return scene;
}

struct RunOutput {
  std::vector<double> t;
  std::vector<Vector> y;
  long steps = 0, rejected = 0, evaluations = 0;
};

struct RunRequest {
  std::string integrator;
  double dt = 0;
  long steps = 0;       // fixed number of steps, or
  double until = NAN;   // an end time (adaptive runs)
  long every = 1;
  double atol = NAN, rtol = NAN;
};

// The size of a scene's state: positions and velocities, or the first-order system's variables.
size_t state_size(const SceneDescription& scene) {
  return scene.mechanical ? 2 * static_cast<size_t>(scene.mechanical->dimensions) * scene.mechanical->bodies.size()
                          : scene.first_order->initial.size();
}

// A number as the wire carries it (wire.hpp): a JSON number, or "inf", "-inf" or "nan".
bool is_wire_number(const json& j) {
  return j.is_number() || (j.is_string() && (j == "inf" || j == "-inf" || j == "nan"));
}

std::string count_of(size_t n, const char* one, const char* many) { return std::to_string(n) + " " + (n == 1 ? one : many); }

// A non-negative whole number of the reply (a run's steps, say), 0 when it has none.
long count_field(const json& reply, const char* key, const std::string& whose) {
  const auto at = reply.find(key);
  if (at == reply.end()) return 0;
  if (!at->is_number_integer() || at->get<long long>() < 0)
    malformed_reply(whose, fmt::format("\"{}\" is not a whole number ≥ 0", key));
  return static_cast<long>(at->get<long long>());
}

RunOutput run(Probe& probe, const CheckScene& scene, const RunRequest& r, Clock::time_point deadline) {
  json request = {{"op", "run"},        {"scene", scene.text}, {"file", fs::path(scene.file).filename().string()},
                  {"integrator", r.integrator}, {"dt", r.dt},      {"every", r.every}};
  if (std::isnan(r.until))
    request["steps"] = r.steps;
  else
    request["until"] = r.until;
  if (!std::isnan(r.atol)) request["atol"] = r.atol;
  if (!std::isnan(r.rtol)) request["rtol"] = r.rtol;
  // Its shape, known before it is asked: a row (a time and a state of the scene's size) at the
  // start, every `every` steps and at the end of a fixed run (a few more, for rounding), and of an
  // adaptive one as many as the server records at most. Every reply is checked against it before
  // anything in it is read: a reply the student's code wrote over the server's ("t": [], 100
  // states of one number) was indexed as it came, and crashed the grader (SIGSEGV, the batch with it).
  const size_t n = state_size(scene.description);
  const double server_rows = std::floor(wire::kMostRunNumbers / static_cast<double>(n + 1));
  const double rows = std::isnan(r.until) ? std::min(static_cast<double>(r.steps / std::max(1L, r.every)) + 3, server_rows)
                                          : server_rows;
  const std::string whose = "the run's reply";
  const json reply = probe.ask(request, deadline, ReplySize{static_cast<size_t>(rows * static_cast<double>(n + 1))});
  const auto t = reply.find("t"), y = reply.find("y");
  if (t == reply.end() || y == reply.end()) malformed_reply(whose, "it has no \"t\" or no \"y\"");
  if (!t->is_array() || !y->is_array()) malformed_reply(whose, "its \"t\" or its \"y\" is not an array");
  if (t->size() != y->size())
    malformed_reply(whose, fmt::format("{} but {}", count_of(t->size(), "time", "times"), count_of(y->size(), "state", "states")));
  if (y->empty()) malformed_reply(whose, "it has no states");
  if (static_cast<double>(y->size()) > rows)
    malformed_reply(whose, fmt::format("{} states, more than this run can make ({})", y->size(), rows));
  RunOutput out;
  for (size_t k = 0; k < t->size(); ++k) {
    const json& time = (*t)[k];
    // (A time is always finite: the server stops a run whose step size is not a number.)
    if (!time.is_number()) malformed_reply(whose, fmt::format("t[{}] is not a finite number", k));
    out.t.push_back(time.get<double>());
    const json& row = (*y)[k];
    if (!row.is_array() || row.size() != n)
      malformed_reply(whose, fmt::format("y[{}] is not {} (the scene's state)", k, count_of(n, "number", "numbers")));
    Vector state(static_cast<Eigen::Index>(n));
    for (size_t i = 0; i < n; ++i) {
      if (!is_wire_number(row[i])) malformed_reply(whose, fmt::format("y[{}][{}] is not a number", k, i));
      state[static_cast<Eigen::Index>(i)] = wire::number(row[i]);
    }
    out.y.push_back(std::move(state));
  }
  out.steps = count_field(reply, "steps", whose);
  out.rejected = count_field(reply, "rejected", whose);
  out.evaluations = count_field(reply, "evaluations", whose);
  return out;
}

// The scene's bodies as motus measures them (energies, momenta), whatever engine moved them.
MechanicalSystem measuring_system(const SceneDescription& scene) {
  std::vector<double> masses;
  for (const auto& b : scene.mechanical->bodies) masses.push_back(b.mass);
  return MechanicalSystem(scene.mechanical->dimensions, masses, scene.mechanical->forces);
}

double energy(const MechanicalSystem& system, const Vector& y) {
  const Eigen::Index n = system.size();
  return system.kinetic_energy(y.tail(n)) + system.potential_energy(y.head(n));
}

// ---- The student's code a test runs --------------------------------------------------------------

// "a, b or c" (`last`: "or", "and").
std::string listed(const std::vector<std::string>& xs, const char* last) {
  if (xs.size() <= 1) return xs.empty() ? std::string() : xs.front();
  return fmt::format("{} {} {}", fmt::join(xs.begin(), xs.end() - 1, ", "), last, xs.back());
}

std::vector<std::string> student_names(const StudentParts& parts) {
  std::vector<std::string> names;
  for (const auto& i : parts.integrators) names.push_back(i.name);
  return names;
}

const StudentIntegrator* student_named(const StudentParts& parts, const std::string& name) {
  for (const auto& i : parts.integrators)
    if (i.name == name) return &i;
  return nullptr;
}

// What the plug-in brings, for a message: "integrators (student:euler, …)", "collision rules", ...
std::string brings(const StudentParts& parts) {
  std::vector<std::string> what;
  if (!parts.integrators.empty()) what.push_back(fmt::format("integrators ({})", listed(student_names(parts), "and")));
  if (parts.collisions) what.push_back("collision rules");
  if (parts.constraints) what.push_back("a constraint projection");
  return what.empty() ? "nothing a test can run" : listed(what, "and");
}

// "student:rk4", "one of student:euler, …": the integrators a test may name, for a message
// (`brief`: the first two of them only, in a message long already — one line is 400 characters).
std::string choices(const StudentParts& parts, bool brief = false) {
  if (!parts.known) return "the plug-in's own, PLUGIN:NAME as its MOTUS_PLUGIN names it";
  const auto names = student_names(parts);
  if (names.size() == 1) return names.front();
  if (brief && names.size() > 2) return fmt::format("one of {}, {}, …", names[0], names[1]);
  return "one of " + listed(names, "or");
}

struct RunsStudent {
  std::string name, kind;  // kind: StudentIntegrator's, or "" when the plug-in's source was not read whole
};

// A name given as `integrator` that is no built-in's: one of the student's, or refused (a name
// the plug-in does not bring made every student's run stop: "unknown integrator", exit 0).
RunsStudent student_named_in(JsonFields& f, const StudentParts& parts, const std::string& name) {
  if (!parts.known) {
    if (name.find(':') == std::string::npos)
      f.fail("integrator", "\"" + name + "\" is neither motus's integrator nor a plug-in's (a plug-in's is PLUGIN:NAME)");
    return {name, ""};
  }
  const StudentIntegrator* s = student_named(parts, name);
  if (!s) {
    const auto names = student_names(parts);
    const std::string guess = did_you_mean(name, names);
    f.fail("integrator", names.empty()   ? fmt::format("\"{}\" is none of the student's integrators: the assignment's "
                                                       "plug-in ({}) brings none (it brings {})",
                                                       name, parts.file, brings(parts))
                         : guess.empty() ? fmt::format("\"{}\" is none of the student's integrators (the assignment's "
                                                       "plug-in, {}, brings {})",
                                                       name, parts.file, listed(names, "and"))
                                         : fmt::format("\"{}\" is none of the student's integrators{}", name, guess));
  }
  return {s->name, s->kind};
}

// The integrator of a test that grades the student's integrator (`what`: "an order test"):
// required, and one the plug-in brings. A test without one, or with motus's own ("rk4" for
// "student:rk4"), ran motus's integrator: every submission passed it, a wrong RK4 too.
// (make_check has refused such a test where the plug-in brings no integrator at all.)
RunsStudent student_integrator(JsonFields& f, const StudentParts& parts, const std::string& what) {
  // (A misspelt field is named as such: JsonFields::fail turns "missing (required)" into its
  // "unknown field, did you mean integrator?".)
  if (!f.has("integrator"))
    f.fail("integrator", fmt::format("missing (required): {} grades the student's integrator, {}", what, choices(parts)));
  const std::string name = f.string("integrator");
  if (integrator_from_name(name)) {
    const std::string same = parts.prefix + ":" + name;
    f.fail("integrator", fmt::format("\"{}\" is motus's own integrator; {} grades the student's code: {}", name, what,
                                     parts.known && student_named(parts, same) ? same : choices(parts)));
  }
  return student_named_in(f, parts, name);
}

// Whether the student's integrator can run the test's scene, as motus's World decides it
// (engine/motus/world.cpp): contacts and sticks are resolved only within motus's own
// symplectic-euler or verlet, and a step of bodies (x and v) cannot run a first-order system.
// Where it cannot, every student's run stopped ("student:rk4 cannot run collisions").
void check_runs_scene(JsonFields& f, const RunsStudent& integrator, const SceneDescription& scene,
                      const StudentParts& parts) {
  if (const auto& m = scene.mechanical) {
    const long balls = std::count_if(m->bodies.begin(), m->bodies.end(), [](const auto& b) { return b.radius > 0; });
    if (!m->sticks.empty() || !m->pins.empty())
      f.fail("integrator", integrator.name + " cannot run the scene's sticks and pins: they are projected within "
                                             "motus's own verlet only");
    if (!m->colliders.empty() || balls >= 2)
      f.fail("integrator", integrator.name + " cannot run the scene's contacts (walls, or two balls or more): they are "
                                             "resolved within motus's own symplectic-euler or verlet only");
    return;
  }
  if (integrator.kind != "mechanical" && integrator.kind != "position_verlet") return;
  std::vector<std::string> first_order;
  for (const auto& i : parts.integrators)
    if (i.kind == "first_order" || i.kind == "adaptive") first_order.push_back(i.name);
  f.fail("integrator", fmt::format("{} steps bodies (x and v), and the test's scene is a first-order system (y): {}",
                                   integrator.name,
                                   first_order.empty() ? std::string("the plug-in brings no integrator that steps one")
                                                       : "use " + listed(first_order, "or")));
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

// The part of a state a check compares: x (positions), v, or all of it.
Vector part(const Vector& y, const std::string& which) {
  const Eigen::Index half = y.size() / 2;
  if (which == "x") return y.head(half);
  if (which == "v") return y.tail(half);
  return y;
}

std::string read_part(JsonFields& f, const SceneDescription& scene) {
  const std::string which = f.string("compare", scene.mechanical ? "x" : "state");
  if (which != "x" && which != "v" && which != "state") f.fail("compare", "must be \"x\", \"v\" or \"state\"");
  if (which != "state" && !scene.mechanical) f.fail("compare", "\"x\" and \"v\" are for scenes of bodies");
  return which;
}

std::vector<double> to_std(const Vector& v) { return {v.data(), v.data() + v.size()}; }

// ---- trajectory ---------------------------------------------------------------------------------

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

// ---- order ----------------------------------------------------------------------------------------

class OrderCheck final : public Check {
public:
  OrderCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts, std::string hint)
      : scene_(load_check_scene(f, test, source)), hint_(std::move(hint)) {
    if (!has_exact_solution(scene_.description))
      throw SceneError(f.path_of("scene"), "an order check needs a scene with an exact solution or reference states");
    const RunsStudent integrator = student_integrator(f, parts, "an order test");
    check_runs_scene(f, integrator, scene_.description, parts);
    integrator_ = integrator.name;
    dt_ = f.positive("dt", scene_.description.dt);
    duration_ = f.positive("duration", scene_.description.duration);
    // (At least two: the order is read at the two finest pairs of step sizes, and one halving
    // makes one pair — where a step whose error does not shrink at all can show any order.)
    halvings_ = static_cast<int>(f.integer("halvings", 4));
    if (halvings_ < 2 || halvings_ > 16)
      f.fail("halvings", fmt::format("must be from 2 to 16 (got {}): the order is read at the two finest pairs of "
                                     "successive step sizes, and {} halving{} make{} {}",
                                     halvings_, halvings_, halvings_ == 1 ? "" : "s", halvings_ == 1 ? "s" : "",
                                     halvings_ == 1 ? "one pair" : halvings_ < 1 ? "none" : "too many runs"));
    which_ = read_part(f, scene_.description);
    expected_ = f.positive("expect");
    tolerance_ = f.positive("tolerance", 0.2);
    // What it usually means when the error does not shrink with h at all (an order below 0.5):
    // then the step itself is wrong, and the hint about what lowers the order would mislead.
    hint_no_order_ = f.string("hint_no_order", "");
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    std::vector<double> hs, errors;
    for (int k = 0; k <= halvings_; ++k) {
      const double h = dt_ / std::ldexp(1.0, k);
      RunRequest r;
      r.integrator = integrator_;
      r.dt = h;
      r.steps = fixed_step_count(duration_, h);
      r.every = r.steps;
      const RunOutput out = grade::run(probe, scene_, r, deadline);
      const auto exact = exact_state(scene_.description, out.t.back());
      if (!exact) throw std::runtime_error("no exact state at t = " + num(out.t.back()));
      const Vector diff = part(out.y.back(), which_) - part(*exact, which_);
      const double error = diff.allFinite() ? diff.cwiseAbs().maxCoeff() : INFINITY;
      hs.push_back(h);
      errors.push_back(error);
    }
    // The orders of the finest kReadPairs pairs of successive step sizes whose errors both stand
    // above rounding (1e-12), each within the tolerance; none when a run blew up (an order from
    // the coarser pairs would pass code that fails at small steps). One pair is not enough: a
    // wrong step whose error does not shrink at all (velocityless Verlet with h for h²) has
    // errors of order 1 whose ratios are chance, and one of them may look like the right order.
    const auto blew_up = std::find_if(errors.begin(), errors.end(), [](double e) { return !std::isfinite(e); });
    struct Pair {
      size_t fine;  // the pair of hs[fine - 1] and hs[fine]
      double order;
    };
    std::vector<Pair> read;  // from the coarser to the finer
    for (size_t k = errors.size() - 1; blew_up == errors.end() && k >= 1 && read.size() < kReadPairs; --k)
      if (errors[k] > kRounding && errors[k - 1] > kRounding)
        read.insert(read.begin(), {k, std::log2(errors[k - 1] / errors[k])});
    std::vector<std::string> orders;
    for (const auto& p : read)
      orders.push_back(fmt::format("{} (h = {} to {})", num(p.order), num(hs[p.fine - 1]), num(hs[p.fine])));
    std::string what;
    if (blew_up != errors.end())
      what = fmt::format("no order: the error at h = {} is not finite (the run blew up, or gave NaN)",
                         num(hs[static_cast<size_t>(blew_up - errors.begin())]));
    else if (read.empty() && std::ranges::all_of(errors, [](double e) { return e <= kRounding; }))
      what = "no order: every error is at rounding's level (below 1e-12)";
    else if (read.empty())
      what = "no order: no two successive step sizes have errors both above rounding's level (1e-12)";
    else if (read.size() == 1)
      what = "global order " + orders.front();
    else
      what = fmt::format("global orders {} and {} between successive halvings",
                         fmt::join(orders.begin(), orders.end() - 1, ", "), orders.back());
    std::vector<std::string> table;
    for (size_t k = 0; k < hs.size(); ++k) table.push_back(fmt::format("h = {}: error {}", num(hs[k]), num(errors[k])));
    const std::string measured = fmt::format("{}, from the errors at the end ({})", what, fmt::join(table, "; "));
    const std::string expected =
        fmt::format("order {} ± {}{}", num(expected_), num(tolerance_),
                    read.size() > 1 ? fmt::format(" at each of the {} finest halvings", read.size()) : "");
    const bool ok = !read.empty() && std::ranges::all_of(read, [&](const Pair& p) {
      return std::abs(p.order - expected_) <= tolerance_;
    });
    if (ok) return pass(measured);
    // (An order below 0: the error grows.)
    const auto lowest = std::ranges::min_element(read, {}, &Pair::order);
    const bool no_order = lowest != read.end() && lowest->order < 0.5 && !hint_no_order_.empty();
    return fail(measured, expected,
                no_order ? fmt::format("the error does not shrink as h does (order {} from h = {} to {}): {}", num(lowest->order),
                                       num(hs[lowest->fine - 1]), num(hs[lowest->fine]), hint_no_order_)
                         : hint_);
  }

private:
  // Pairs read: two, not all (of halvings = 3's three, the reference RK4 on the Lorenz system
  // gives 5.24 at the coarsest, before its error settles into h⁴; 3.86 and 3.87 at the two finest).
  static constexpr size_t kReadPairs = 2;
  static constexpr double kRounding = 1e-12;  // an error at or below this is rounding's
  CheckScene scene_;
  std::string integrator_, which_;
  double dt_, duration_, expected_, tolerance_;
  int halvings_;
  std::string hint_, hint_no_order_;
};

// ---- stability ----------------------------------------------------------------------------------

class StabilityCheck final : public Check {
public:
  StabilityCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts, std::string hint)
      : scene_(load_check_scene(f, test, source)), hint_(std::move(hint)) {
    const auto& m = scene_.description.mechanical;
    if (!m || m->dimensions != 1 || m->bodies.size() != 1)
      throw SceneError(f.path_of("scene"), "a stability check runs one body in 1-D (an oscillator)");
    const RunsStudent integrator = student_integrator(f, parts, "a stability test");
    check_runs_scene(f, integrator, scene_.description, parts);
    integrator_ = integrator.name;
    omega_ = f.positive("omega", 1);
    steps_ = f.integer("steps", 10000);
    if (steps_ < 100 || steps_ > 10'000'000) f.fail("steps", "must be from 100 to 10,000,000");
    limit_ = f.positive("expect");
    tolerance_ = f.positive("tolerance", 0.01);
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    double lo = 0.5 * limit_, hi = 1.5 * limit_;
    bool low_ok = bounded(probe, lo, deadline), high_ok = bounded(probe, hi, deadline);
    // A limit far from the expected one still gets measured: that number is what tells a student
    // which mistake it is (explicit Euler's 10,000 steps stay bounded only below ωh ≈ 0.037, a
    // scheme that never blows up has none). The bracket moves by factors of two, ten at most.
    for (int i = 0; !low_ok && i < kBracketMoves; ++i) hi = lo, lo *= 0.5, low_ok = bounded(probe, lo, deadline);
    for (int i = 0; high_ok && i < kBracketMoves; ++i) lo = hi, hi *= 2, high_ok = bounded(probe, hi, deadline);
    const std::string expected = fmt::format("largest stable step ωh = {} within {}%", num(limit_), num(100 * tolerance_));
    if (!low_ok)
      return fail(fmt::format("the run blows up at every step tried, down to ωh = {} ({} steps each)", num(lo), steps_),
                  expected, hint_);
    if (high_ok)
      return fail(fmt::format("the run stays bounded at every step tried, up to ωh = {} ({} steps each)", num(hi), steps_),
                  expected, hint_);
    for (int i = 0; i < 12; ++i) {
      const double mid = 0.5 * (lo + hi);
      (bounded(probe, mid, deadline) ? lo : hi) = mid;
    }
    const double measured = 0.5 * (lo + hi);
    const std::string text = fmt::format("largest stable step ωh = {} (bisection over {} steps each)", num(measured), steps_);
    return std::abs(measured - limit_) <= tolerance_ * limit_ ? pass(text) : fail(text, expected, hint_);
  }

private:
  static constexpr int kBracketMoves = 10;  // (from 2⁻¹⁰ to 2¹⁰ times the expected limit's bracket)

  // Whether steps_ steps of h = z/ω keep the amplitude √(x² + (v/ω)²) within 1000× its start.
  bool bounded(Probe& probe, double z, Clock::time_point deadline) const {
    RunRequest r;
    r.integrator = integrator_;
    r.dt = z / omega_;
    r.steps = steps_;
    r.every = std::max(1L, steps_ / 100);
    const RunOutput out = grade::run(probe, scene_, r, deadline);
    auto amplitude = [&](const Vector& y) { return std::hypot(y[0], y[1] / omega_); };
    const double start = amplitude(out.y.front());
    for (const auto& y : out.y)
      if (!(amplitude(y) <= 1000 * start)) return false;  // NaN and ∞ count as blown up
    return true;
  }

  CheckScene scene_;
  std::string integrator_;
  double omega_, limit_, tolerance_;
  long steps_;
  std::string hint_;
};

// ---- energy ----------------------------------------------------------------------------------------

class EnergyCheck final : public Check {
public:
  EnergyCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts, std::string hint)
      : scene_(load_check_scene(f, test, source)), hint_(std::move(hint)) {
    if (!scene_.description.mechanical) throw SceneError(f.path_of("scene"), "an energy check needs a scene of bodies");
    const RunsStudent integrator = student_integrator(f, parts, "an energy test");
    check_runs_scene(f, integrator, scene_.description, parts);
    integrator_ = integrator.name;
    dt_ = f.positive("dt", scene_.description.dt);
    steps_ = f.integer("steps");
    if (steps_ < 1 || steps_ > 10'000'000) f.fail("steps", "must be from 1 to 10,000,000");
    auto e = f.object("expect");
    if (e.has("bounded")) bounded_ = e.positive("bounded");
    if (e.has("growth_per_step")) growth_ = e.positive("growth_per_step");
    tolerance_ = e.positive("tolerance", 1e-9);
    e.reject_unknown();
    if (std::isnan(bounded_) == std::isnan(growth_)) f.fail("expect", "needs exactly one of bounded, growth_per_step");
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    RunRequest r;
    r.integrator = integrator_;
    r.dt = dt_;
    r.steps = steps_;
    r.every = std::max(1L, steps_ / 200);
    const RunOutput out = grade::run(probe, scene_, r, deadline);
    const MechanicalSystem system = measuring_system(scene_.description);
    const double e0 = energy(system, out.y.front());
    // A state that is not a number (or infinite) is said to be one, and where it was first seen: a
    // run of NaN read as one whose "state changed by at most 0 of its size" (std::max(moved, NaN) is
    // moved). The state is looked at every r.every steps, so it went wrong after the last finite one.
    for (size_t k = 0; k < out.y.size(); ++k) {
      if (out.y[k].allFinite()) continue;
      auto step_at = [&](size_t i) { return std::lround((out.t[i] - out.t.front()) / dt_); };
      const std::string became = out.y[k].hasNaN() ? "not a number (NaN)" : "infinite";
      const std::string measured =
          k == 0 ? fmt::format("the state was {} at the start", became)
                 : fmt::format("the state became {} by step {} (t = {}): it is looked at every {} of the {} steps, and was "
                               "finite at step {} (t = {})",
                               became, step_at(k), num(out.t[k]), r.every, out.steps, step_at(k - 1), num(out.t[k - 1]));
      const std::string want = !std::isnan(growth_)
                                   ? fmt::format("energy × {}^{}, from states that are numbers", num(growth_), out.steps)
                                   : "a run whose states are numbers, and whose energy stays within " + num(bounded_);
      return fail(measured, want,
                  "an operation that gives NaN — 0/0, ∞ − ∞, the square root of a negative number — or a variable used "
                  "before it is set; a state that becomes infinite first grew without bound. Print x and v in your step "
                  "to see where they first go wrong.");
    }
    if (!std::isnan(growth_)) {
      const double ratio = energy(system, out.y.back()) / e0;
      const double expected = std::pow(growth_, static_cast<double>(out.steps));
      const std::string measured = fmt::format("energy × {} after {} steps", num(ratio), out.steps);
      const std::string want = fmt::format("× {} = {}^{} (to {} relative)", num(expected), num(growth_), out.steps, num(tolerance_));
      return std::abs(ratio / expected - 1) <= tolerance_ ? pass(measured) : fail(measured, want, hint_);
    }
    // Bounded: small, and no larger in the second half of the run than in the first — for a
    // run that moves at all (a method that leaves the state alone keeps every energy).
    double moved = 0;
    for (const auto& y : out.y) moved = std::max(moved, (y - out.y.front()).norm() / std::max(out.y.front().norm(), 1e-300));
    if (!(moved > 0.01))
      return fail(fmt::format("the state changed by at most {} of its size over {} steps", num(moved), out.steps),
                  "a run that moves (and keeps its energy within " + num(bounded_) + ")", hint_);
    double first = 0, second = 0;
    for (size_t k = 0; k < out.y.size(); ++k) {
      const double error = std::abs(energy(system, out.y[k]) - e0) / std::abs(e0);
      double& half = 2 * k < out.y.size() ? first : second;
      half = std::isfinite(error) ? std::max(half, error) : INFINITY;
    }
    const std::string measured =
        fmt::format("largest |E − E₀|/|E₀| {} in the first half of {} steps, {} in the second", num(first), out.steps, num(second));
    const bool ok = first <= bounded_ && second <= bounded_ && second <= 1.5 * first + 1e-12;
    return ok ? pass(measured)
              : fail(measured, fmt::format("at most {}, and not growing (the second half ≤ 1.5 × the first)", num(bounded_)),
                     hint_);
  }

private:
  CheckScene scene_;
  std::string integrator_;
  double dt_;
  long steps_;
  double bounded_ = NAN, growth_ = NAN, tolerance_ = 1e-9;
  std::string hint_;
};

// ---- adaptive ------------------------------------------------------------------------------------

class AdaptiveCheck final : public Check {
public:
  // (Its failures say what each failed condition usually means; the test's hint is for a run that
  // stops or runs out of time, which the grader shows.)
  AdaptiveCheck(JsonFields& f, const json& test, const SceneSource& source, const StudentParts& parts)
      : scene_(load_check_scene(f, test, source)) {
    if (!has_exact_solution(scene_.description))
      throw SceneError(f.path_of("scene"), "an adaptive check needs a scene with an exact solution");
    const RunsStudent integrator = student_integrator(f, parts, "an adaptive test");
    // (A fixed-step one never changes its step: every submission failed "its step size changes".)
    if (!integrator.kind.empty() && integrator.kind != "adaptive") {
      std::vector<std::string> adaptive;
      for (const auto& i : parts.integrators)
        if (i.kind == "adaptive") adaptive.push_back(i.name);
      f.fail("integrator", fmt::format("{} takes fixed steps; an adaptive test needs an adaptive integrator of the "
                                       "student's: {}",
                                       integrator.name,
                                       adaptive.empty() ? "the plug-in brings none" : listed(adaptive, "or")));
    }
    check_runs_scene(f, integrator, scene_.description, parts);
    integrator_ = integrator.name;
    tolerance_ = f.positive("tolerance");
    first_step_ = f.positive("first_step", scene_.description.dt);
    duration_ = f.positive("duration", scene_.description.duration);
    max_error_ = f.positive("max_error");
    // motus's own adaptive method at the same tolerance, run in the same check: the student's
    // error may be at most `factor` times its error.
    if (f.has("compare_with")) {
      const auto builtin = integrator_from_name(f.string("compare_with"));
      if (!builtin || !info(*builtin).adaptive) f.fail("compare_with", "must name one of motus's adaptive integrators");
      compare_with_ = *builtin;
      factor_ = f.positive("factor", 2);
    }
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    RunRequest r;
    r.integrator = integrator_;
    r.dt = first_step_;
    r.until = scene_.description.start_time + duration_;
    r.every = 1;  // every step's time: the step sizes the controller chose
    r.atol = r.rtol = tolerance_;
    const RunOutput out = grade::run(probe, scene_, r, deadline);
    const double error = error_at_end(out.y.back(), out.t.back());
    // The steps it took, but the last (shortened to land on the end): an adaptive run's change
    // with the error. A controller that keeps h as it is can still beat fixed-step RK4 with the
    // doubling's extrapolation alone, and must not pass as adaptive.
    double smallest = INFINITY, largest = 0;
    for (size_t i = 1; i + 1 < out.t.size(); ++i) {
      smallest = std::min(smallest, out.t[i] - out.t[i - 1]);
      largest = std::max(largest, out.t[i] - out.t[i - 1]);
    }
    const bool adapts = largest >= 2 * smallest;
    // motus's own fixed-step RK4, halving h until it is as accurate — or until it has spent
    // more evaluations than the student's run, which settles the comparison.
    long rk4_evaluations = -1;
    bool rk4_needs_more = false;
    for (int k = 0; k < 30 && std::isfinite(error); ++k) {
      Simulation sim(scene_.description, Integrator::Rk4);
      const double h = first_step_ / std::ldexp(1.0, k);
      if (fixed_step_count(r.until - sim.time(), h) * 4 > std::max(out.evaluations, 1L) * 2) {
        rk4_needs_more = true;
        break;
      }
      sim.advance(r.until, h, Tolerance{});
      if (error_at_end(sim.state(), sim.time()) <= error) {
        rk4_evaluations = sim.evaluations();
        break;
      }
    }
    double peer_error = NAN;
    std::string peer;
    if (compare_with_) {
      Simulation sim(scene_.description, *compare_with_);
      sim.advance(r.until, first_step_, Tolerance{tolerance_, tolerance_});
      peer_error = error_at_end(sim.state(), sim.time());
      peer = fmt::format("; motus's {} at the same tolerance: error {}", info(*compare_with_).name, num(peer_error));
    }
    const std::string measured = fmt::format(
        "at tolerance {}: error {} at t = {} after {} steps ({} rejected; h from {} to {}) and {} evaluations; motus's "
        "fixed-step rk4 needs {} evaluations for that error",
        num(tolerance_), num(error), num(out.t.back()), out.steps, out.rejected, num(smallest), num(largest),
        out.evaluations, rk4_needs_more ? "more than " + std::to_string(out.evaluations) : std::to_string(rk4_evaluations)) +
        peer + (out.evaluations == 0 ? " (your step never called f.derivative: it cannot have moved the state)" : "");
    const bool lands = std::abs(out.t.back() - r.until) <= 1e-9 * std::max(1.0, std::abs(r.until));
    const bool fewer = rk4_needs_more || (rk4_evaluations > 0 && out.evaluations < rk4_evaluations);
    const bool accurate = error <= max_error_;
    const bool as_good = !compare_with_ || error <= factor_ * peer_error;
    const bool ok = lands && accurate && fewer && as_good && adapts;
    if (ok) return pass(measured);
    // Each condition that failed, and what it usually means: the test's own hint would name every
    // cause at once. Steps 5 times the one before, with none rejected, are the mark of an error
    // estimate that is exactly 0 (next_step_size(h, 0) is 5 h).
    bool grew_fivefold = out.rejected == 0 && out.t.size() > 3;
    for (size_t i = 2; grew_fivefold && i + 1 < out.t.size(); ++i)
      grew_fivefold = std::abs((out.t[i] - out.t[i - 1]) / (out.t[i - 1] - out.t[i - 2]) - 5) < 1e-6;
    std::vector<std::string> causes;
    if (!lands)
      causes.push_back(fmt::format("The run stopped at t = {}, not at its end, t = {}.", num(out.t.back()), num(r.until)));
    if (!adapts)
      causes.push_back(fmt::format("The step size never changed (h from {} to {}): next_step_size keeps h; it must be "
                                   "h · 0.9 · ratio^(-1/5), between h/5 and 5 h.",
                                   num(smallest), num(largest)));
    if (grew_fivefold)
      causes.push_back("Every step was 5 times the one before and none was rejected: the error was exactly 0 at every "
                       "step, so rk4_doubling_step never sets error (it must be (y_half - y_full)/15).");
    else if (!accurate || !as_good)
      causes.push_back(fmt::format("The error at the end is larger than {}: steps whose error is above the tolerance were "
                                   "accepted, or the step is less accurate than it should be. rk4_doubling_step's error "
                                   "must be (y_half - y_full)/15, and it returns y_half + error (fifth order; y_half alone "
                                   "is fourth).",
                                   // (the bound it missed: within the test's own, it can still miss motus's by the factor)
                                   !accurate ? num(max_error_)
                                             : fmt::format("{} × motus's {} ({})", num(factor_), info(*compare_with_).name,
                                                           num(factor_ * peer_error))));
    if (!fewer && !grew_fivefold)
      causes.push_back("It needed more evaluations than fixed-step RK4 at the same error: steps smaller than they need "
                       "be. The controller's exponent is -1/5 (a larger error, a smaller step: written -1.0 / 5, since "
                       "-1 / 5 is 0 in integer arithmetic), and the factor 0.9.");
    causes.push_back("Step doubling calls your rk4_step: a wrong rk4_step fails this test too (see the rk4 tests).");
    return fail(measured,
                fmt::format("the run lands on t = {}, its error is at most {}{}, it needs fewer evaluations "
                            "than fixed-step RK4 at the same error, and its step size changes with the error (the "
                            "largest step at least twice the smallest)",
                            num(r.until), num(max_error_),
                            compare_with_ ? fmt::format(" and at most {} × motus's {}", num(factor_), info(*compare_with_).name)
                                          : ""),
                fmt::format("{}", fmt::join(causes, " ")));
  }

private:
  double error_at_end(const Vector& y, double t) const {
    const auto exact = exact_state(scene_.description, t);
    if (!exact) return INFINITY;
    const Vector diff = y - *exact;
    return diff.allFinite() ? diff.cwiseAbs().maxCoeff() : INFINITY;
  }
  CheckScene scene_;
  std::string integrator_;
  double tolerance_, first_step_, duration_, max_error_;
  std::optional<Integrator> compare_with_;
  double factor_ = 2;
};

// ---- call ------------------------------------------------------------------------------------------

// The functions a call test calls (motus/student/plugin.hpp names them), their parameters in the
// order they declare them (true: a vector) and their outputs.
struct CallSignature {
  const char* op;
  const char* function;
  std::vector<std::pair<std::string, bool>> parameters, outputs;
};
const CallSignature kCallSignatures[] = {
    {"collide_balls", "collide_balls",
     {{"m_a", false}, {"v_a", true}, {"m_b", false}, {"v_b", true}, {"n", true}, {"e", false}},
     {{"v_a", true}, {"v_b", true}}},
    {"bounce_off_wall", "bounce_off_wall", {{"v", true}, {"n", true}, {"e", false}}, {{"v", true}}},
    {"balls_impact", "time_of_impact",
     {{"p_a", true}, {"v_a", true}, {"r_a", false}, {"p_b", true}, {"v_b", true}, {"r_b", false}},
     {{"t", false}}},
    {"plane_impact", "time_of_impact_with_plane", {{"p", true}, {"v", true}, {"r", false}, {"n", true}, {"offset", false}},
     {{"t", false}}},
};
const CallSignature& call_signature(const std::string& op) {
  return *std::find_if(std::begin(kCallSignatures), std::end(kCallSignatures), [&](const auto& s) { return op == s.op; });
}

class CallCheck final : public Check {
public:
  CallCheck(JsonFields& f, const json& test, const StudentParts& parts, std::string hint) : hint_(std::move(hint)) {
    if (parts.known && !parts.collisions)
      f.fail("kind", fmt::format("a call test calls the student's collision functions, and the assignment's plug-in ({}) "
                                 "brings none (it brings {})",
                                 parts.file, brings(parts)));
    op_ = f.string("op");
    if (std::none_of(std::begin(kCallSignatures), std::end(kCallSignatures), [&](const auto& s) { return op_ == s.op; }))
      f.fail("op", "must be one of collide_balls, bounce_off_wall, balls_impact, plane_impact");
    f.use("args");
    f.use("expect");
    if (!test.contains("args") || !test.at("args").is_object()) f.fail("args", "must be an object of the call's arguments");
    if (!test.contains("expect") || !test.at("expect").is_object() || test.at("expect").empty())
      f.fail("expect", "must be an object of the outputs expected");
    args_ = test.at("args");
    expect_ = test.at("expect");
    tolerance_ = f.positive("tolerance", 1e-9);
    // Every argument the function takes, and only those, each a finite number or a vector of one
    // size; every output expected one the function gives. (A slip here went to every student's
    // code: a missing argument stopped their run, a misspelt output read as their reply lacking it.)
    const CallSignature& signature = call_signature(op_);
    size_t size = 0;
    for (const auto& [name, vector] : signature.parameters) {
      const std::string at = f.path_of("args") + "." + name;
      if (!args_.contains(name)) throw SceneError(at, std::string("missing (") + signature.function + " takes it)");
      const json& a = args_.at(name);
      auto finite = [](const json& x) { return x.is_number() && std::isfinite(x.get<double>()); };
      if (!vector && !finite(a)) throw SceneError(at, "must be a finite number, not " + a.dump());
      if (vector && (!a.is_array() || a.empty() || a.size() > 3 || !std::all_of(a.begin(), a.end(), finite)))
        throw SceneError(at, "must be a vector of 1 to 3 finite numbers, not " + a.dump());
      if (vector && size != 0 && a.size() != size)
        throw SceneError(at, fmt::format("has {} numbers where the call's other vectors have {}", a.size(), size));
      if (vector) size = a.size();
    }
    for (const auto& [name, value] : args_.items())
      if (std::none_of(signature.parameters.begin(), signature.parameters.end(), [&](const auto& p) { return name == p.first; }))
        throw SceneError(f.path_of("args") + "." + name, std::string("is no argument of ") + signature.function);
    for (const auto& [name, value] : expect_.items()) {
      const std::string at = f.path_of("expect") + "." + name;
      const auto output = std::find_if(signature.outputs.begin(), signature.outputs.end(), [&](const auto& o) { return name == o.first; });
      if (output == signature.outputs.end())
        throw SceneError(at, fmt::format("is no output of {} (it gives {})", signature.function,
                                         fmt::join(signature.outputs | std::views::keys, ", ")));
      const bool vector = output->second;
      auto number = [](const json& x) { return x.is_number() || x == "inf" || x == "-inf"; };
      if (vector ? !value.is_array() || value.size() != size || !std::all_of(value.begin(), value.end(), number) : !number(value))
        throw SceneError(at, vector ? fmt::format("must be a vector of {} numbers (as the arguments), not {}", size, value.dump())
                                    : "must be a number (or \"inf\"), not " + value.dump());
    }
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    json request = args_;
    request["op"] = op_;
    const json reply = probe.ask(request, deadline);
    // The student reads which of their functions was called, with what: an argument is no
    // expected value, and "v_a = (0.5, 0)" alone does not say whose v_a.
    std::string measured = call_as_written() + " gives ", expected;
    const size_t measured_start = measured.size();
    bool ok = true;
    for (const auto& [key, want] : expect_.items()) {
      if (!reply.contains(key)) malformed_reply("the reply of " + call_as_written(), "it has no \"" + key + "\"");
      const json& value = reply.at(key);
      // (A number where one is expected, a vector of 1 to 3 dimensions where one is: the server's.)
      if (want.is_array() ? !value.is_array() || value.empty() || value.size() > 3 ||
                                !std::all_of(value.begin(), value.end(), is_wire_number)
                          : !is_wire_number(value))
        malformed_reply("the reply of " + call_as_written(),
                        fmt::format("its \"{}\" is not {}", key, want.is_array() ? "a vector of 1 to 3 numbers" : "a number"));
      const auto got = want.is_array() ? wire::numbers(value) : std::vector<double>{wire::number(value)};
      const auto wanted = want.is_array() ? wire::numbers(want) : std::vector<double>{wire::number(want)};
      ok = ok && all_close(got, wanted, tolerance_);
      measured += fmt::format("{}{} = {}", measured.size() == measured_start ? "" : ", ", key, nums(got));
      expected += fmt::format("{}{} = {}", expected.empty() ? "" : ", ", key, nums(wanted));
    }
    return ok ? pass(measured) : fail(measured, expected + fmt::format(" (to {})", num(tolerance_)), hint_);
  }

private:
  // "collide_balls(m_a = 1, v_a = (1, 0), ...)": the student's own function (motus/student/
  // plugin.hpp names them) with its arguments in the order it declares them.
  std::string call_as_written() const {
    const CallSignature& s = call_signature(op_);
    std::string call = std::string(s.function) + "(";
    for (const auto& [p, vector] : s.parameters) {
      const json& a = args_.at(p);
      call += fmt::format("{}{} = {}", call.back() == '(' ? "" : ", ", p, vector ? nums(wire::numbers(a)) : num(wire::number(a)));
    }
    return call + ")";
  }

  std::string op_;
  json args_, expect_;
  double tolerance_;
  std::string hint_;
};

// ---- step ------------------------------------------------------------------------------------------

// One step of the student's integrator called directly on one coordinate whose acceleration (or
// derivative) is a polynomial of the time alone, c0 + c1 t + …: no scene's force depends on the
// time, so this is where a stage taken at the wrong time shows. `hints` may give, output by output,
// what it being wrong usually means: a failure shows the first of them whose output is wrong.
class StepCheck final : public Check {
public:
  StepCheck(JsonFields& f, const json& test, const StudentParts& parts, std::string hint) : hint_(std::move(hint)) {
    const RunsStudent integrator = student_integrator(f, parts, "a step test");
    integrator_ = integrator.name;
    of_time_ = f.numbers("of_time", -1);
    if (of_time_.empty() || of_time_.size() > 8) f.fail("of_time", "needs 1 to 8 coefficients c0, c1, … of c0 + c1 t + …");
    request_ = {{"op", "step"}, {"integrator", integrator_}, {"of_time", of_time_}, {"t", f.number("t")},
                {"h", f.positive("h")}};
    for (const char* key : {"x", "v", "y"})
      if (f.has(key)) request_[key] = f.numbers(key, 1);
    if (f.has("y") == (f.has("x") || f.has("v")) || f.has("x") != f.has("v"))
      f.fail("y", "needs y (a first-order or adaptive integrator) or x and v (point masses), one number each");
    // What the integrator's kind takes and gives (cli/serve_command.cpp, step): a step of bodies
    // given y, or an output its kind does not give, stopped every student's run.
    const bool first_order = integrator.kind == "first_order" || integrator.kind == "adaptive";
    if (!integrator.kind.empty() && first_order != f.has("y"))
      f.fail(first_order ? "x" : "y", first_order ? integrator_ + " steps y' = f(t, y): give y (one number), not x and v"
                                                  : integrator_ + " steps bodies: give x and v (one number each), not y");
    static const std::map<std::string, std::vector<std::string>> gives = {
        {"first_order", {"y"}},
        {"adaptive", {"y", "accepted", "h"}},
        {"mechanical", {"x", "v"}},
        {"position_verlet", {"x_start", "x", "x_previous"}}};
    const auto given = gives.find(integrator.kind);
    if (f.has("y")) {
      request_["atol"] = f.positive("atol", 1);
      request_["rtol"] = f.positive("rtol", 1);
    }
    f.use("expect");
    f.use("hints");
    if (!test.contains("expect") || !test.at("expect").is_object() || test.at("expect").empty())
      f.fail("expect", "must be an object of the outputs expected (x, v, y, x_start, x_previous, accepted, h)");
    expect_ = test.at("expect");
    for (const auto& [key, value] : expect_.items()) {
      static const std::vector<std::string> outputs = {"x", "v", "y", "x_start", "x_previous", "accepted", "h"};
      if (std::find(outputs.begin(), outputs.end(), key) == outputs.end())
        throw SceneError(f.path_of("expect") + "." + key, "is no output of a step (x, v, y, x_start, x_previous, accepted, h)");
      if (given != gives.end() && std::find(given->second.begin(), given->second.end(), key) == given->second.end())
        throw SceneError(f.path_of("expect") + "." + key,
                         fmt::format("is no output of a step of {} (it gives {})", integrator_, listed(given->second, "and")));
      const json& number = value.is_array() && value.size() == 1 ? value[0] : value;
      if (!number.is_number() || !std::isfinite(number.get<double>()))
        throw SceneError(f.path_of("expect") + "." + key, "must be one finite number (a step moves one coordinate), not " + value.dump());
    }
    if (test.contains("hints")) {
      const json& hints = test.at("hints");
      if (!hints.is_array()) f.fail("hints", "must be an array of [OUTPUT, HINT] pairs, the most telling first");
      for (const auto& pair : hints) {
        if (!pair.is_array() || pair.size() != 2 || !pair[0].is_string() || !pair[1].is_string() ||
            !expect_.contains(pair[0].get<std::string>()))
          f.fail("hints", "each must be [OUTPUT, HINT]: an output in expect, and what it being wrong usually means");
        hints_.push_back({pair[0].get<std::string>(), pair[1].get<std::string>()});
      }
    }
    tolerance_ = f.positive("tolerance", 1e-9);
  }

  CheckResult run(Probe& probe, Clock::time_point deadline) const override {
    const json reply = probe.ask(request_, deadline);
    std::string measured, expected;
    std::vector<std::string> wrong;
    for (const auto& [key, want] : expect_.items()) {
      if (!reply.contains(key))
        malformed_reply("the reply of a step of your integrator " + integrator_, "it has no \"" + key + "\"");
      const json value = reply.at(key).is_array() ? reply.at(key) : json::array({reply.at(key)});
      // (One coordinate: each output of a step is one number.)
      if (value.size() != 1 || !is_wire_number(value[0]))
        malformed_reply("the reply of a step of your integrator " + integrator_, fmt::format("its \"{}\" is not one number", key));
      const auto got = wire::numbers(value);
      const auto wanted = wire::numbers(want.is_array() ? want : json::array({want}));
      if (!all_close(got, wanted, tolerance_)) wrong.push_back(key);
      measured += fmt::format("{}{} = {}", measured.empty() ? "" : ", ", key, nums(got));
      expected += fmt::format("{}{} = {}", expected.empty() ? "" : ", ", key, nums(wanted));
    }
    const bool mechanical = request_.contains("x");
    std::vector<std::string> terms;
    for (size_t k = 0; k < of_time_.size(); ++k)
      if (of_time_[k] != 0 || of_time_.size() == 1)
        terms.push_back(k == 0 ? num(of_time_[k]) : fmt::format("{}{}", of_time_[k] == 1 ? "" : num(of_time_[k]) + " ", k == 1 ? std::string("t") : "t^" + std::to_string(k)));
    const std::string from =
        mechanical ? fmt::format("x = {}, v = {}", num(request_["x"][0].get<double>()), num(request_["v"][0].get<double>()))
                   : fmt::format("y = {}", num(request_["y"][0].get<double>()));
    measured += fmt::format(" after one step of h = {} from t = {}, {}, on {} = {}", num(request_["h"].get<double>()),
                            num(request_["t"].get<double>()), from, mechanical ? "x'' = a(t)" : "y' = f(t)",
                            fmt::join(terms, " + "));
    if (wrong.empty()) return pass(measured);
    // The hint of the first wrong output in the order of `hints` (the others usually follow from it:
    // a wrong start makes the step's result wrong too), else the test's own.
    std::string hint = hint_;
    for (const auto& [key, text] : hints_)
      if (std::find(wrong.begin(), wrong.end(), key) != wrong.end()) {
        hint = text;
        break;
      }
    return fail(measured, expected + fmt::format(" (to {})", num(tolerance_)), hint);
  }

private:
  std::string integrator_;
  std::vector<double> of_time_;
  json request_, expect_;
  std::vector<std::pair<std::string, std::string>> hints_;
  double tolerance_ = 1e-9;
  std::string hint_;
};

// ---- scene -----------------------------------------------------------------------------------------

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

// ---- project -----------------------------------------------------------------------------------------

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

std::string scene_for_the_sandbox(const std::string& text, const std::vector<std::string>& sets) {
  json document = json::parse(text);
  for (const auto& s : sets) apply_override(document, s);
  document.erase("reference");
  return document.dump();
}

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
  if (kind == "trajectory") return std::make_unique<TrajectoryCheck>(test, raw, scenes, parts, hint);
  if (kind == "order") return std::make_unique<OrderCheck>(test, raw, scenes, parts, hint);
  if (kind == "stability") return std::make_unique<StabilityCheck>(test, raw, scenes, parts, hint);
  if (kind == "energy") return std::make_unique<EnergyCheck>(test, raw, scenes, parts, hint);
  if (kind == "adaptive") return std::make_unique<AdaptiveCheck>(test, raw, scenes, parts);
  if (kind == "call") return std::make_unique<CallCheck>(test, raw, parts, hint);
  if (kind == "scene") return std::make_unique<SceneCheck>(test, raw, scenes, parts, hint);
  if (kind == "project") return std::make_unique<ProjectCheck>(test, raw, parts, hint);
  if (kind == "step") return std::make_unique<StepCheck>(test, raw, parts, hint);
  test.fail("kind", "must be trajectory, order, stability, energy, adaptive, call, scene, project or step");
}

}  // namespace motus::grade
