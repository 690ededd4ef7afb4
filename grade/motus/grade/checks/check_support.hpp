#pragma once
// What the check kinds (checks/*_check.cpp) share: the words and numbers of their messages, a
// test's scene loaded and run by the student's code, and which of the student's code a test runs.
// Internal to the grade library: for check.cpp and the files beside this one alone.
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "motus/grade/check.hpp"
#include "motus/grade/probe.hpp"
#include "motus/scene.hpp"
#include "motus/scene_file/json_fields.hpp"
#include "motus/systems/mechanical_system.hpp"
#include "motus/vector.hpp"

namespace motus::grade::detail {

using Clock = std::chrono::steady_clock;

// ---- Words and numbers for the messages -------------------------------------------------------

std::string num(double x);
std::string nums(const std::vector<double>& xs);

CheckResult pass(std::string measured);
CheckResult fail(const std::string& measured, const std::string& expected, const std::string& hint);

// |a − b| within tolerance, scaled by the size of what was expected (at least 1).
bool close(double measured, double expected, double tolerance);
bool all_close(const std::vector<double>& measured, const std::vector<double>& expected, double tolerance);

// "a, b or c" (`last`: "or", "and").
std::string listed(const std::vector<std::string>& xs, const char* last);

// ---- Scenes and runs ------------------------------------------------------------------------------

CheckScene load_check_scene(JsonFields& f, const nlohmann::json& test, const SceneSource& source);

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

// A number as the wire carries it (wire.hpp): a JSON number, or "inf", "-inf" or "nan".
bool is_wire_number(const nlohmann::json& j);

// The scene run by the student's code as `r` asks, its reply checked against the shape the request
// asks for (malformed_reply) before anything in it is read.
RunOutput run(Probe& probe, const CheckScene& scene, const RunRequest& r, Clock::time_point deadline);

// The scene's bodies as motus measures them (energies, momenta), whatever engine moved them.
MechanicalSystem measuring_system(const SceneDescription& scene);
double energy(const MechanicalSystem& system, const Vector& y);

std::vector<double> to_std(const Vector& v);

// ---- The student's code a test runs --------------------------------------------------------------

// What the plug-in brings, for a message: "integrators (student:euler, …)", "collision rules", ...
std::string brings(const StudentParts& parts);

// "student:rk4", "one of student:euler, …": the integrators a test may name, for a message
// (`brief`: the first two of them only, in a message long already — one line is 400 characters).
std::string choices(const StudentParts& parts, bool brief = false);

struct RunsStudent {
  std::string name, kind;  // kind: StudentIntegrator's, or "" when the plug-in's source was not read whole
};

// A name given as `integrator` that is no built-in's: one of the student's, or refused (a name
// the plug-in does not bring made every student's run stop: "unknown integrator", exit 0).
RunsStudent student_named_in(JsonFields& f, const StudentParts& parts, const std::string& name);

// The integrator of a test that grades the student's integrator (`what`: "an order test"):
// required, and one the plug-in brings. A test without one, or with motus's own ("rk4" for
// "student:rk4"), ran motus's integrator: every submission passed it, a wrong RK4 too.
// (make_check has refused such a test where the plug-in brings no integrator at all.)
RunsStudent student_integrator(JsonFields& f, const StudentParts& parts, const std::string& what);

// Whether the student's integrator can run the test's scene, as motus's World decides it
// (engine/motus/world.cpp): contacts and sticks are resolved only within motus's own
// symplectic-euler or verlet, and a step of bodies (x and v) cannot run a first-order system.
// Where it cannot, every student's run stopped ("student:rk4 cannot run collisions").
void check_runs_scene(JsonFields& f, const RunsStudent& integrator, const SceneDescription& scene,
                      const StudentParts& parts);

}  // namespace motus::grade::detail
