// A step test: one step of the student's integrator on one coordinate whose acceleration (or
// derivative) is a polynomial of the time, its outputs against the test's.
#include "motus/grade/checks/check_kinds.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "motus/grade/checks/check_support.hpp"
#include "motus/grade/wire.hpp"
#include "motus/scene_error.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

namespace {

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

}  // namespace

std::unique_ptr<Check> detail::make_step_check(JsonFields& f, const json& test, const StudentParts& parts, const std::string& hint) {
  return std::make_unique<StepCheck>(f, test, parts, hint);
}

}  // namespace motus::grade
