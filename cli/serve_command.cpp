#include "serve_command.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "integrator_choice.hpp"
#include "motus/grade/server_filter.hpp"
#include "motus/grade/wire.hpp"
#include "plugin_loading.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/simulation.hpp"

namespace motus::cli {
namespace {

using nlohmann::json;
namespace wire = grade::wire;

// The dimensions a request works in: 1, 2 or 3, as a scene's (the parts' pins and walls hold 3).
int dimensions(const json& request, const char* key) {
  const long d = request.at(key).is_array() ? static_cast<long>(request.at(key).size()) : request.at(key).get<long>();
  if (d < 1 || d > 3) throw std::invalid_argument(std::string(key) + ": 1, 2 or 3 dimensions, not " + std::to_string(d));
  return static_cast<int>(d);
}

std::vector<double> point(const json& request, const char* key, int d) {
  std::vector<double> p = wire::numbers(request.at(key));
  if (static_cast<int>(p.size()) != d)
    throw std::invalid_argument(std::string(key) + ": needs " + std::to_string(d) + " numbers");
  return p;
}

json run(const json& r) {
  const std::string file = r.value("file", std::string("scene"));
  const SceneDescription scene = parse_scene(r.at("scene").get<std::string>(), file, r.value("set", std::vector<std::string>{}));
  const Method method = method_for(file, scene, r.value("integrator", scene.integrator));
  Simulation sim(scene, method, plugins().parts());
  const double dt = r.value("dt", scene.dt);
  const long every = std::max(1L, r.value("every", 1L));
  const double end = r.contains("until") ? wire::number(r.at("until"))
                                          : sim.time() + static_cast<double>(r.value("steps", 1L)) * dt;
  const Tolerance tolerance{r.value("atol", scene.atol), r.value("rtol", scene.rtol)};
  json t = json::array(), y = json::array();
  // What one run may record (wire.hpp): a step-size control that shrinks the step without end
  // records rows until memory runs out — and a JSON array that big cannot even be destroyed then
  // (nlohmann's destructor allocates: std::terminate, "killed by SIGABRT" in place of the student's error).
  auto row = [&](const Simulation& s) {
    if (static_cast<double>(t.size() + 1) * static_cast<double>(s.state().size() + 1) > wire::kMostRunNumbers)
      throw std::runtime_error("by t = " + std::to_string(s.time()) + " the run had taken " + std::to_string(sim.steps()) +
                               " steps and recorded " + std::to_string(t.size()) +
                               " states, the most one run may record: a step size that shrinks without end?");
    t.push_back(wire::number(s.time()));
    y.push_back(wire::numbers(s.state()));
  };
  row(sim);
  long last_row = 0;
  sim.advance(end, dt, tolerance, [&](const Simulation& s) {
    if (s.steps() % every == 0) {
      row(s);
      last_row = s.steps();
    }
  });
  if (last_row != sim.steps()) row(sim);
  return {{"t", t}, {"y", y}, {"steps", sim.steps()}, {"rejected", sim.rejected()}, {"evaluations", sim.evaluations()}};
}

const ExternalCollisionRules& collisions() {
  const ExternalCollisionRules* rules = plugins().parts().collisions;
  if (!rules) throw std::invalid_argument("the plug-in brings no collision response");
  return *rules;
}

json collide_balls(const json& r) {
  const auto& rules = collisions();
  const int d = dimensions(r, "v_a");
  std::vector<double> v_a = point(r, "v_a", d), v_b = point(r, "v_b", d);
  const std::vector<double> n = point(r, "n", d);
  check_external(rules.collide_balls(rules.self, d, v_a.data(), v_b.data(), wire::number(r.at("m_a")),
                                     wire::number(r.at("m_b")), n.data(), wire::number(r.at("e"))),
                 "collide_balls", rules.error, rules.self);
  return {{"v_a", wire::numbers(v_a)}, {"v_b", wire::numbers(v_b)}};
}

json bounce_off_wall(const json& r) {
  const auto& rules = collisions();
  const int d = dimensions(r, "v");
  std::vector<double> v = point(r, "v", d);
  const std::vector<double> n = point(r, "n", d);
  check_external(rules.bounce_off_wall(rules.self, d, v.data(), n.data(), wire::number(r.at("e"))), "bounce_off_wall",
                 rules.error, rules.self);
  return {{"v", wire::numbers(v)}};
}

json balls_impact(const json& r) {
  const auto& rules = collisions();
  const int d = dimensions(r, "p_a");
  const auto p_a = point(r, "p_a", d), v_a = point(r, "v_a", d), p_b = point(r, "p_b", d), v_b = point(r, "v_b", d);
  double t = 0;
  check_external(rules.balls_impact(rules.self, d, p_a.data(), v_a.data(), wire::number(r.at("r_a")), p_b.data(),
                                    v_b.data(), wire::number(r.at("r_b")), &t),
                 "time_of_impact", rules.error, rules.self);
  return {{"t", wire::number(t)}};
}

json plane_impact(const json& r) {
  const auto& rules = collisions();
  const int d = dimensions(r, "p");
  const auto p = point(r, "p", d), v = point(r, "v", d), n = point(r, "n", d);
  double t = 0;
  check_external(rules.plane_impact(rules.self, d, p.data(), v.data(), wire::number(r.at("r")), n.data(),
                                    wire::number(r.at("offset")), &t),
                 "time_of_impact_with_plane", rules.error, rules.self);
  return {{"t", wire::number(t)}};
}

// c0 + c1 t + c2 t² + …: the `step` op's acceleration or derivative, whatever the state.
struct PolynomialOfTime {
  std::vector<double> coefficients;  // c0, c1, c2, …
  double value_at(double t) const {  // (Horner's rule)
    double value = 0;
    for (auto k = coefficients.rbegin(); k != coefficients.rend(); ++k) value = value * t + *k;
    return value;
  }
};

// One step of the student's integrator "student:NAME", called directly (the `step` check), on one
// coordinate whose acceleration (point masses) or derivative (first order) is a polynomial of the
// time alone: its right one-step answers are known exactly, and they show whether each stage is
// taken at its own time (no scene's force depends on the time).
json step(const json& r) {
  const std::string name = r.at("integrator").get<std::string>();
  const auto method = plugins().integrator(name);
  if (!method || !method->is_external()) throw std::invalid_argument("step: the plug-in brings no integrator \"" + name + "\"");
  const ExternalIntegrator& integrator = method->outside();
  PolynomialOfTime polynomial{wire::numbers(r.at("of_time"))};
  const double t = wire::number(r.at("t"));
  double h = wire::number(r.at("h"));
  const std::string what = r.value("function", name);
  auto check = [&](int status) { check_external(status, what.c_str(), integrator.error, integrator.self); };
  if (integrator.kind == kExternalAdaptive || integrator.kind == kExternalFirstOrder) {
    std::vector<double> y = wire::numbers(r.at("y"));
    if (y.size() != 1) throw std::invalid_argument("step: y must be one number");
    const ExternalFirstOrder f{1, &polynomial, [](void* self, double time, const double*, double* dydt) {
                                 dydt[0] = static_cast<const PolynomialOfTime*>(self)->value_at(time);
                               }};
    if (integrator.kind == kExternalFirstOrder) {
      check(integrator.step(integrator.self, &f, t, h, y.data()));
      return {{"y", wire::numbers(y)}};
    }
    int accepted = 0;
    check(integrator.try_step(integrator.self, &f, t, &h, y.data(), wire::number(r.at("atol")), wire::number(r.at("rtol")), &accepted));
    return {{"y", wire::numbers(y)}, {"accepted", accepted}, {"h", wire::number(h)}};
  }
  std::vector<double> x = wire::numbers(r.at("x")), v = wire::numbers(r.at("v"));
  if (x.size() != 1 || v.size() != 1) throw std::invalid_argument("step: x and v must be one number each");
  const ExternalMechanical s{1, &polynomial, [](void* self, double time, const double*, const double*, double* a) {
                               a[0] = static_cast<const PolynomialOfTime*>(self)->value_at(time);
                             }};
  if (integrator.kind == kExternalMechanical) {
    check(integrator.step_mechanical(integrator.self, &s, t, h, x.data(), v.data()));
    return {{"x", wire::numbers(x)}, {"v", wire::numbers(v)}};
  }
  std::vector<double> previous(1, 0.0);
  check(integrator.verlet_start(integrator.self, &s, t, h, x.data(), v.data(), previous.data()));
  const std::vector<double> start = previous;
  check(integrator.verlet_step(integrator.self, &s, t, h, x.data(), previous.data(), v.data()));
  return {{"x_start", wire::numbers(start)}, {"x", wire::numbers(x)}, {"x_previous", wire::numbers(previous)}};
}

json project(const json& r) {
  const ExternalConstraintRules* rules = plugins().parts().constraints;
  if (!rules) throw std::invalid_argument("the plug-in brings no constraint projection");
  const int d = dimensions(r, "dimensions");
  std::vector<double> inverse_mass = wire::numbers(r.at("inverse_mass")), radius = wire::numbers(r.at("radius"));
  const int n = static_cast<int>(inverse_mass.size());
  std::vector<double> x = wire::numbers(r.at("x"));
  if (static_cast<int>(radius.size()) != n || static_cast<int>(x.size()) != n * d)
    throw std::invalid_argument("project: inverse_mass, radius and x do not agree on the number of bodies");
  std::vector<ExternalStick> sticks;
  for (const auto& s : r.at("sticks")) sticks.push_back({s.at(0).get<int>(), s.at(1).get<int>(), wire::number(s.at(2))});
  std::vector<ExternalPin> pins;
  for (const auto& p : r.at("pins")) {
    ExternalPin pin{p.at(0).get<int>(), {0, 0, 0}};
    const auto at = wire::numbers(p.at(1));
    for (int k = 0; k < d && k < static_cast<int>(at.size()); ++k) pin.position[k] = at[static_cast<size_t>(k)];
    pins.push_back(pin);
  }
  std::vector<ExternalWall> walls;
  for (const auto& w : r.at("walls")) {
    ExternalWall wall{{0, 0, 0}, wire::number(w.at(1))};
    const auto normal = wire::numbers(w.at(0));
    for (int k = 0; k < d && k < static_cast<int>(normal.size()); ++k) wall.normal[k] = normal[static_cast<size_t>(k)];
    walls.push_back(wall);
  }
  for (const auto& s : sticks)
    if (s.a < 0 || s.a >= n || s.b < 0 || s.b >= n) throw std::invalid_argument("project: a stick names no body");
  for (const auto& p : pins)
    if (p.body < 0 || p.body >= n) throw std::invalid_argument("project: a pin names no body");
  static long requests = 0;  // each request is a run of its own (ExternalConstraintSet::id)
  const ExternalConstraintSet set{-(++requests),
                                  d,
                                  n,
                                  inverse_mass.data(),
                                  radius.data(),
                                  static_cast<int>(sticks.size()),
                                  sticks.data(),
                                  static_cast<int>(pins.size()),
                                  pins.data(),
                                  static_cast<int>(walls.size()),
                                  walls.data(),
                                  r.value("iterations", 1)};
  check_external(rules->project(rules->self, &set, x.data()), "satisfy_constraints", rules->error, rules->self);
  return {{"x", wire::numbers(x)}};
}

json handle(const json& request) {
  const std::string op = request.at("op").get<std::string>();
  if (op == "run") return run(request);
  if (op == "collide_balls") return collide_balls(request);
  if (op == "bounce_off_wall") return bounce_off_wall(request);
  if (op == "balls_impact") return balls_impact(request);
  if (op == "plane_impact") return plane_impact(request);
  if (op == "project") return project(request);
  if (op == "step") return step(request);
  throw std::invalid_argument("unknown op \"" + op + "\"");
}

}  // namespace

CLI::App* add_serve_command(CLI::App& app, ServeOptions& o) {
  auto* serve = app.add_subcommand("serve",
                                   "The student's side of `motus grade` (run inside its sandbox): answers one request "
                                   "per line on standard input with raw outputs, one line each");
  serve->add_option("--plugin", o.plugins, "The student's plug-in")->required()->type_name("FILE.so");
  serve->group("");  // not for users: `motus grade` starts it
  return serve;
}

int serve_command(const ServeOptions& o) {
  // The answers go to the original standard output; anything else this process prints —
  // the student's own std::cout included — goes to standard error, so that its printing cannot
  // corrupt an answer. (Code in the plug-in could still write to the answers' descriptor; it
  // gains nothing: serve is never told the expected values.)
  auto failed_write = [] {
    tell("motus: the run failed: standard output: could not be written ({})\n", std::strerror(errno));
    return kExitFailure;
  };
  std::FILE* out = nullptr;
  try {
    out = keep_data_apart_from_standard_output();
  } catch (const std::runtime_error&) {
    return failed_write();
  }
  // Before the student's code runs at all (a plug-in's constructors run as it loads): no new
  // processes and no memory outside this one's address space, so that the sandbox's memory limit
  // holds all of the student's code at once.
  try {
    grade::install_server_filter();
  } catch (const std::exception& e) {
    tell("motus serve: {} (this machine's, not the submission's)\n", e.what());
    return kExitFailure;
  }
  // Said before the student's code runs (its constructors run as the plug-in loads): how the grader
  // knows that a failure after it is not bubblewrap's (see probe.cpp).
  if (std::fprintf(out, "%s\n", std::string(grade::wire::kServing).c_str()) < 0 || std::fflush(out) != 0)
    return failed_write();
  load_plugins(o.plugins);
  std::string line;
  while (std::getline(std::cin, line)) {
    json reply;
    try {
      reply = handle(json::parse(line));
      reply["ok"] = true;
    } catch (const ExternalCodeFailed& e) {  // (the student's code threw: see probe.cpp)
      reply = {{"ok", false}, {"error", e.what()}, {"threw", true}};
    } catch (const std::exception& e) {
      reply = {{"ok", false}, {"error", e.what()}};
    }
    const std::string text = reply.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
    if (std::fputs(text.c_str(), out) == EOF || std::fflush(out) != 0) return failed_write();
  }
  return 0;
}

}  // namespace motus::cli
