#pragma once
// What a test of an assignment checks, and how: each kind reads its definition (a test's
// JSON object, every field checked when the assignment is loaded), asks the student's code
// for raw outputs through the Probe, and judges them here, outside the sandbox, against
// numbers that come from somewhere — the course's table, theory (orders, stability limits,
// conserved quantities), the analytic solution of the scene, or motus's own built-in
// method run in the same check.
//
// Kinds (docs: assignments/README.md, "Writing a test"):
//   trajectory  a run's states at given steps, against given values
//   order       the global order measured by halving the step, against the exact solution
//   stability   the largest stable step, found by bisection, against theory
//   energy      energy over a long run: bounded, or growing by a given factor per step
//   adaptive    an adaptive run: its error at the end, and fewer evaluations than fixed RK4
//   call        one of the student's functions with given arguments, against given outputs
//   scene       a scene run with the student's parts: velocities, energy, momentum, no
//               tunnelling, stick lengths, pins, bounce heights
//   project     the student's constraint projection on given positions
//   step        one step of the student's integrator on y' = c0 + c1 t + ..., against given values
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "motus/grade/probe.hpp"
#include "motus/scene.hpp"
#include "motus/scene_file/json_fields.hpp"

namespace motus::grade {

struct CheckResult {
  bool passed = false;
  std::string output;  // what was measured, what was expected, and what that usually means
};

// Where a test's scene files are: a shipped scene's name, or a path relative to the test file.
struct SceneSource {
  std::function<std::string(const std::string& name)> shipped;  // name → file
  std::function<std::string(const std::string& name)> guess;    // a name that is none → ", did you mean X?" or ""
  std::string tests_folder;
};

// What the assignment's plug-in brings, as its source registers it (the MOTUS_PLUGIN of a file
// the assignment provides, read when the tests are: assignment.cpp, read_plugin_parts): the
// student's integrators a test may run ("student:rk4") and their kinds, and whether the student's
// collision rules or constraint projection take motus's place in a run. A test that names an
// integrator the plug-in does not bring failed every submission ("unknown integrator"); one that
// names motus's own, or none, graded motus's code and passed every submission.
struct StudentIntegrator {
  std::string name;  // as a test names it: "student:rk4"
  std::string kind;  // "first_order", "mechanical", "position_verlet" or "adaptive" (plugin.hpp's calls)
};
struct StudentParts {
  // Whether the plug-in's source was found and read whole (every registration a plain string
  // literal): only then is a name checked against those it brings. Otherwise a test of the
  // student's integrator still needs one, and one that is no built-in's.
  bool known = false;
  std::string file;    // where it was read ("plugin.cpp"), for messages
  std::string prefix;  // its MOTUS_PLUGIN name ("student"): "PREFIX:NAME" names its integrators
  std::vector<StudentIntegrator> integrators;
  bool collisions = false, constraints = false;
};

// A scene a check runs: the JSON text sent to the student's side (scene_for_the_sandbox) and
// its description (for the grader's own measurements).
struct CheckScene {
  std::string file, text;
  SceneDescription description;
};

// A scene file's text as the student's side gets it: the test's "set"s applied, and its
// "reference" states — values the student's run is judged against — left out. (The scene's
// name for an exact solution stays: the student's run needs none, and it is no value.)
// `text` is a scene that parse_scene has read with `sets`.
std::string scene_for_the_sandbox(const std::string& text, const std::vector<std::string>& sets);

class Check {
public:
  virtual ~Check() = default;
  // Runs the check; a ProbeFailure (the student's code failed) escapes to the grader.
  virtual CheckResult run(Probe& probe, std::chrono::steady_clock::time_point deadline) const = 0;
};

// The check a test's definition asks for. Throws SceneError (field path within the test) or
// SceneFileError (a scene it names) when the definition cannot be used — among them a test that
// would grade none of the student's code (motus's own integrator, or none, where the student's is
// what is graded) or code the plug-in does not bring (`parts`).
std::unique_ptr<Check> make_check(JsonFields& test, const SceneSource& scenes, const StudentParts& parts,
                                  const std::string& hint);

}  // namespace motus::grade
