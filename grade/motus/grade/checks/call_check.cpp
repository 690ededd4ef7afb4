// A call test: one of the student's collision functions called with the test's arguments, its
// outputs against the test's.
#include "motus/grade/checks/check_kinds.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <ranges>

#include "motus/grade/checks/check_support.hpp"
#include "motus/grade/wire.hpp"
#include "motus/scene_error.hpp"

using nlohmann::json;

namespace motus::grade {

using namespace detail;

namespace {

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

}  // namespace

std::unique_ptr<Check> detail::make_call_check(JsonFields& f, const json& test, const StudentParts& parts, const std::string& hint) {
  return std::make_unique<CallCheck>(f, test, parts, hint);
}

}  // namespace motus::grade
