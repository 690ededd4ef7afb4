// The helpers the check kinds (checks/*_check.cpp) share: the words and numbers of their messages,
// a test's scene loaded and run by the student's code, and which of the student's code a test runs.
#include "motus/grade/checks/check_support.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "motus/grade/wire.hpp"
#include "motus/integrate/integrator_catalog.hpp"
#include "motus/scene_error.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/scene_file/scene_overrides.hpp"
#include "motus/scene_file/spelling.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace motus::grade {
namespace {

// (The helpers of the helpers below: none of the check kinds needs them.)

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

// The size of a scene's state: positions and velocities, or the first-order system's variables.
size_t state_size(const SceneDescription& scene) {
  return scene.mechanical ? 2 * static_cast<size_t>(scene.mechanical->dimensions) * scene.mechanical->bodies.size()
                          : scene.first_order->initial.size();
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

}  // namespace

namespace detail {

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

CheckResult pass(std::string measured) { return {true, "Measured: " + measured + "."}; }

CheckResult fail(const std::string& measured, const std::string& expected, const std::string& hint) {
  std::string out = "Measured: " + measured + ".\nExpected: " + expected + ".";
  if (!hint.empty()) out += "\nThis usually means: " + hint;
  return {false, out};
}

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

std::string listed(const std::vector<std::string>& xs, const char* last) {
  if (xs.size() <= 1) return xs.empty() ? std::string() : xs.front();
  return fmt::format("{} {} {}", fmt::join(xs.begin(), xs.end() - 1, ", "), last, xs.back());
}

// ---- Scenes and runs ------------------------------------------------------------------------------

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
    // (One format: moved out of check.cpp, GCC 12 warned falsely on "\"" + string here, PR105651.)
    if (!fs::is_regular_file(scene.file))
      f.fail("scene", fmt::format("\"{}\" is no shipped scene{} (motus list shows them; a file of the tests' own is a "
                                  "scene_file)",
                                  f.string("scene"), source.guess ? source.guess(f.string("scene")) : std::string()));
  }
  f.use("set");  // read by hand below
  const std::vector<std::string> sets = read_sets(test, f.path());
  const std::string text = read_text(scene.file);
  scene.description = parse_scene(text, scene.file, sets);
  scene.text = scene_for_the_sandbox(text, sets);
  return scene;
}

bool is_wire_number(const json& j) {
  return j.is_number() || (j.is_string() && (j == "inf" || j == "-inf" || j == "nan"));
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

MechanicalSystem measuring_system(const SceneDescription& scene) {
  std::vector<double> masses;
  for (const auto& b : scene.mechanical->bodies) masses.push_back(b.mass);
  return MechanicalSystem(scene.mechanical->dimensions, masses, scene.mechanical->forces);
}

double energy(const MechanicalSystem& system, const Vector& y) {
  const Eigen::Index n = system.size();
  return system.kinetic_energy(y.tail(n)) + system.potential_energy(y.head(n));
}

std::vector<double> to_std(const Vector& v) { return {v.data(), v.data() + v.size()}; }

// ---- The student's code a test runs --------------------------------------------------------------

std::string brings(const StudentParts& parts) {
  std::vector<std::string> what;
  if (!parts.integrators.empty()) what.push_back(fmt::format("integrators ({})", listed(student_names(parts), "and")));
  if (parts.collisions) what.push_back("collision rules");
  if (parts.constraints) what.push_back("a constraint projection");
  return what.empty() ? "nothing a test can run" : listed(what, "and");
}

std::string choices(const StudentParts& parts, bool brief) {
  if (!parts.known) return "the plug-in's own, PLUGIN:NAME as its MOTUS_PLUGIN names it";
  const auto names = student_names(parts);
  if (names.size() == 1) return names.front();
  if (brief && names.size() > 2) return fmt::format("one of {}, {}, …", names[0], names[1]);
  return "one of " + listed(names, "or");
}

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

}  // namespace detail

// (check.hpp's, here beside load_check_scene: the text the student's side gets of every test's scene.)
std::string scene_for_the_sandbox(const std::string& text, const std::vector<std::string>& sets) {
  json document = json::parse(text);
  for (const auto& s : sets) apply_override(document, s);
  document.erase("reference");
  return document.dump();
}

}  // namespace motus::grade
