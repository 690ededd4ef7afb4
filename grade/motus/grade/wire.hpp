#pragma once
// The probe protocol between `motus grade` and `motus serve` (the student's code, in its
// sandbox): one JSON object per line each way. The grader sends inputs — a scene and an
// integrator to run, or one function of the student's to call with its arguments — and the
// server sends back raw outputs only (states, velocities, times). Every comparison with an
// expected value is made by the grader, outside the sandbox: no expected value ever enters it.
//
//   {"op": "run", "scene": TEXT, "file": NAME, "integrator": NAME, "dt": H,
//    "steps": N | "until": T, "every": K, "atol": A, "rtol": R}
//     → {"ok": true, "t": [...], "y": [[...], ...], "steps": S, "rejected": R, "evaluations": E}
//       (y = [x; v] for bodies; a row at the start, every K steps, and at the end. TEXT is the
//       scene with the test's sets applied and its reference states left out:
//       check.hpp's scene_for_the_sandbox)
//   {"op": "collide_balls", "m_a", "v_a", "m_b", "v_b", "n", "e"}     → {"ok": true, "v_a", "v_b"}
//   {"op": "bounce_off_wall", "v", "n", "e"}                           → {"ok": true, "v"}
//   {"op": "balls_impact", "p_a", "v_a", "r_a", "p_b", "v_b", "r_b"}   → {"ok": true, "t"}
//   {"op": "plane_impact", "p", "v", "r", "n", "offset"}               → {"ok": true, "t"}
//   {"op": "project", "dimensions", "inverse_mass", "radius", "sticks": [[a, b, L]...],
//    "pins": [[body, [x...]]...], "walls": [[[n...], offset]...], "iterations", "x"} → {"ok": true, "x"}
//   {"op": "step", "integrator", "of_time": [c0, c1, ...], "t", "h", "y" (with "atol", "rtol")
//    | "x", "v"}  → one step of the student's integrator on y' (or x'') = c0 + c1 t + ...:
//       {"ok": true, "y"} (first order), {"ok": true, "y", "accepted", "h"} (adaptive),
//       {"ok": true, "x", "v"} (bodies), {"ok": true, "x_start", "x", "x_previous"} (velocityless Verlet)
//   anything that fails → {"ok": false, "error": "one line"}
// Numbers that are not finite travel as the strings "inf", "-inf" and "nan".
// Before it loads the student's plug-in (before any of the student's code has run) the server
// says kServing, once: a server that fails without it never got as far as the student's code.
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace motus::grade::wire {

// The server's first line (see above).
constexpr std::string_view kServing = R"({"serving":true})";

// The most numbers one run's reply records, rows × (the state's size + 1): the server stops a run
// past them with an error of its own (a step-size control that shrinks the step without end
// records rows until memory runs out), and the grader reads no reply larger.
constexpr double kMostRunNumbers = 5e6;

inline nlohmann::json number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  return x;
}

inline double number(const nlohmann::json& j) {
  if (j.is_number()) return j.get<double>();
  if (j.is_string()) {
    const std::string s = j.get<std::string>();
    if (s == "inf") return std::numeric_limits<double>::infinity();
    if (s == "-inf") return -std::numeric_limits<double>::infinity();
  }
  return std::numeric_limits<double>::quiet_NaN();
}

template <class Numbers>
nlohmann::json numbers(const Numbers& xs) {
  nlohmann::json out = nlohmann::json::array();
  for (double x : xs) out.push_back(number(x));
  return out;
}

inline std::vector<double> numbers(const nlohmann::json& j) {
  std::vector<double> out;
  if (j.is_array())
    for (const auto& x : j) out.push_back(number(x));
  return out;
}

}  // namespace motus::grade::wire
