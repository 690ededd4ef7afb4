// `motus grade` against a hostile student's submissions (found by an audit): what they did must
// be said as it is — a NaN is no error of 0, a state that is not a number did not "change by at
// most 0", a compile stopped at the grader's CPU limit is no bug of GCC's — and every bad input,
// an unknown assignment too, still leaves a results.json that says what was wrong.
#include <cmath>
#include <csignal>
#include <sstream>
#include <string>

#include "grade_harness.hpp"
#include "motus/grade/build.hpp"
#include "motus/grade/sandbox.hpp"

namespace {

using namespace motus_test;
using nlohmann::json;

std::string output_of(const json& result, const std::string& name) {
  const json* t = test_named(result, name);
  if (!t) {
    ADD_FAILURE() << "no test " << name << " in " << result.dump(2);
    return "";
  }
  return (*t)["output"].get<std::string>();
}

// ---------------------------------------------------------------------------------------------------
// 1. An error estimate that is not a number

// rk4_doubling_step setting error = NaN: std::fmax(ratio, NaN) kept the ratio at 0, so the step
// was accepted as one of error 0 — rk4-doubling.zero-error and .step-time passed, and the kepler
// and lorenz tests said "the error was exactly 0 at every step". motus's own adaptive integrators
// reject a step whose error is NaN (!(err <= 1)) and their controller proposes no step after it
// (h · NaN), which stops the run: so it is for the student's, whatever their next_step_size does
// with a NaN (the auditor's returned 5 h for one), with a message that says what it was.
TEST(GradeSubmissions, AnErrorEstimateThatIsNotANumberIsNoErrorOfZero) {
  NEEDS_SANDBOX();
  TempDir dir;
  const auto defs = definitions("integrators");
  json tests = json::array();
  for (const auto& [name, test] : defs)
    if (name.rfind("rk4-doubling.", 0) == 0) tests.push_back(test);
  ASSERT_GE(tests.size(), 6u);  // (kepler, lorenz, step-time, zero-error, large-error, moderate-error)
  const fs::path assignment = integrators_with_tests(dir, "doubling", tests);
  const std::string error_line = "  error = (y_half - y_full) / 15;\n  return y_half + error;";
  const std::string nan_error = "  error = Vector::Constant(y.size(), std::nan(\"\"));\n  return y_half;";
  const std::vector<std::pair<std::string, fs::path>> submissions = {
      {"nan-error", integrators_solution_with(dir, "nan-error", error_line, nan_error)},
      {"nan-error-5h", integrators_solution_with(dir, "nan-error-5h", error_line, nan_error)}};
  for (const auto& [name, submission] : submissions) ASSERT_FALSE(submission.empty()) << name;
  {  // (and a next_step_size that makes 5 h of a NaN ratio)
    const fs::path file = submissions[1].second / "integrators.cpp";
    std::string source = read_file(file);
    const std::string zero = "if (error_ratio == 0) return 5 * h;";
    const size_t at = source.find(zero);
    ASSERT_NE(at, std::string::npos);
    source.replace(at, zero.size(), "if (error_ratio == 0 || error_ratio != error_ratio) return 5 * h;");
    write_file(file, source);
  }
  for (const auto& [name, submission] : submissions) {
    const fs::path results = dir / (name + ".json");
    const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", results.string()});
    ASSERT_EQ(r.status, 0) << name << ": " << r.err;
    const json result = read_json(results);
    expect_valid_gradescope(result);
    EXPECT_EQ(result["score"], 0) << name << ": " << r.out;  // no test of the step doubling passes
    for (const auto& test : tests) {
      const std::string output = output_of(result, test["name"].get<std::string>());
      EXPECT_EQ(output.find("exactly 0"), std::string::npos) << name << ": " << output;
      EXPECT_EQ(output.rfind("Your code stopped the run: student:rk4-doubling: ", 0), 0u) << name << ": " << output;
      EXPECT_NE(output.find("the error estimate your step set is not a number: error[0] = NaN"), std::string::npos)
          << name << ": " << output;
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// 2. A state that is not a number in an energy test

// symplectic_euler_step making x NaN: the energy test said "the state changed by at most 0 of its
// size" (std::max(moved, NaN) is moved). It says the state became NaN, and where: the energy test
// looks at the state every steps/200 steps (checks/energy_check.cpp), so the first NaN it sees is at
// that step, the start (step 0) being the last finite one.
TEST(GradeSubmissions, AStateThatIsNotANumberInAnEnergyTestIsSaidToBeOne) {
  NEEDS_SANDBOX();
  TempDir dir;
  const json test = definitions("integrators").at("symplectic-euler.energy");
  const fs::path assignment = integrators_with_tests(dir, "energy", json::array({test}));
  const std::string anchor =
      "void symplectic_euler_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {\n";
  const fs::path submission =
      integrators_solution_with(dir, "nan-state", anchor, anchor + "  x.setConstant(std::nan(\"\"));\n");
  ASSERT_FALSE(submission.empty());
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  EXPECT_EQ(result["score"], 0) << r.out;
  const std::string output = output_of(result, "symplectic-euler.energy");
  EXPECT_EQ(output.find("changed by at most"), std::string::npos) << output;
  const long steps = test["steps"].get<long>();
  const long every = std::max(1L, steps / 200);
  const double dt = test["dt"].get<double>();
  std::ostringstream t;
  t << static_cast<double>(every) * dt;
  EXPECT_NE(output.find("Measured: the state became not a number (NaN) by step " + std::to_string(every) + " (t = " + t.str() +
                        "): it is looked at every " + std::to_string(every) + " of the " + std::to_string(steps) +
                        " steps, and was finite at step 0 (t = 0)."),
            std::string::npos)
      << output;
  EXPECT_EQ(output.find(test["hint"].get<std::string>()), std::string::npos) << output;  // (its hint is about energy)
}

// ---------------------------------------------------------------------------------------------------
// 3. A compile stopped by its CPU limit

// What g++ said when the grader's CPU limit (RLIMIT_CPU, 60 s for a compile) killed cc1plus, as the
// audit recorded it (30 static_asserts of a constexpr 1000 × 1000 loop): the driver reports its
// child's SIGXCPU as an internal compiler error and exits with status 4.
const std::string kCpuLimitedCompile =
    "g++: internal compiler error: CPU time limit exceeded signal terminated program cc1plus\n"
    "Please submit a full bug report, with preprocessed source (by using -freport-bug).\n"
    "See <file:///usr/share/doc/gcc-12/README.Bugs> for instructions.\n";
// One of the errors a constexpr loop past GCC's own limit gives (the audit's other case: 250 lines
// of these came before the line above, which fell past the 40 lines shown).
const std::string kConstexprLoopError =
    "/submission/integrators.cpp:9:36: error: non-constant condition for static assertion\n"
    "    9 | #define S(k) static_assert(spin(k) != 12345);\n"
    "      |                            ~~~~~~~~^~~~~~~~\n"
    "/submission/integrators.cpp:11:1:   in 'constexpr' expansion of 'spin(10)'\n"
    "/submission/integrators.cpp:8:70: error: 'constexpr' loop iteration count exceeds limit of 262144 (use "
    "'-fconstexpr-loop-limit=' to increase the limit)\n";

motus::grade::Limits compile_limits() {
  motus::grade::Limits limits;
  limits.cpu_seconds = 60;  // (build.cpp's; the line below says it)
  return limits;
}

// The line that says so: one line, first, naming the limit (build.cpp's Limits) and what uses it up.
void expect_cpu_line(const std::string& shown, const motus::grade::Limits& limits, bool reported_as_a_bug = true) {
  const std::string line = shown.substr(0, shown.find('\n'));
  std::ostringstream seconds;
  seconds << limits.cpu_seconds;
  EXPECT_EQ(line.rfind("Compiling used up the " + seconds.str() + " s of CPU the grader gives a compile", 0), 0u) << shown;
  EXPECT_NE(line.find("constexpr"), std::string::npos) << line;
  if (reported_as_a_bug) {
    EXPECT_NE(line.find("not a bug in GCC to report"), std::string::npos) << line;
  }
}

TEST(GradeSubmissions, ACompileStoppedAtItsCpuLimitSaysSoFirstNotAsABugInGcc) {
  const auto limits = compile_limits();
  motus::grade::Ending ended;
  ended.exited = true;
  ended.status = 4;
  // The driver's words, as they were: the line first, then the compiler's, then how it ended.
  const std::string shown = motus::grade::compiler_messages(kCpuLimitedCompile, ended, limits, 61);
  expect_cpu_line(shown, limits);
  EXPECT_EQ(shown.substr(shown.find('\n') + 1), "The compiler said:\n" + kCpuLimitedCompile + "(the compiler exited with status 4)\n");

  // 250 lines of errors before it: the line is still first, never cut away with the rest.
  std::string long_output;
  for (int i = 0; i < 50; ++i) long_output += kConstexprLoopError;
  long_output += kCpuLimitedCompile;
  const std::string cut = motus::grade::compiler_messages(long_output, ended, limits, 70);
  expect_cpu_line(cut, limits);
  EXPECT_NE(cut.find("more lines left out"), std::string::npos) << cut;
  EXPECT_EQ(cut.find("internal compiler error: CPU time limit"), std::string::npos) << cut;  // (past the cut)

  // The driver itself killed at the limit (SIGXCPU) says the same.
  motus::grade::Ending killed;
  killed.signal = SIGXCPU;
  expect_cpu_line(motus::grade::compiler_messages("", killed, limits, 61), limits, false);

  // Only the compiler's own report of its limit counts: a student's #error with the same words is an
  // error like any other, and an ordinary compile error is shown as it was.
  ended.status = 1;
  const std::string forged =
      "/submission/integrators.cpp:1:2: error: #error g++: internal compiler error: CPU time limit exceeded\n"
      "    1 | #error g++: internal compiler error: CPU time limit exceeded\n"
      "      |  ^~~~~\n";
  EXPECT_EQ(motus::grade::compiler_messages(forged, ended, limits, 1),
            "The compiler said:\n" + forged + "(the compiler exited with status 1)\n");
  EXPECT_EQ(motus::grade::compiler_messages(kConstexprLoopError, ended, limits, 1),
            "The compiler said:\n" + kConstexprLoopError + "(the compiler exited with status 1)\n");
}

// A student who wrote rk4_step(…, Vector y) (the value, not the handout's VectorInOut) saw only the linker's
// "undefined reference to `student::rk4_step(…, Eigen::Ref<Eigen::Matrix<double, -1, 1, 0, -1, 1>, 0,
// Eigen::InnerStride<1> >)'", in Eigen's words and not the handout's (an audit of plausible mistakes). The
// build's output says first which function, that other parameters make another function, and how the
// handout's types read there; the linker's words follow unchanged.
TEST(GradeSubmissions, AFunctionDefinedWithOtherParametersIsNamedInTheHandoutsWords) {
  const auto limits = compile_limits();
  motus::grade::Ending ended;
  ended.exited = true;
  ended.status = 1;
  const std::string handout = read_file(fs::path(kAssignments) / "integrators/integrators.hpp");
  const std::string linker =
      "/usr/bin/ld: /tmp/ccLCEwbe.o: in function `motus_plugin':\n"
      "plugin.cpp:(.text+0x25e): undefined reference to `student::rk4_step(student::FirstOrderSystem const&, double, "
      "double, Eigen::Ref<Eigen::Matrix<double, -1, 1, 0, -1, 1>, 0, Eigen::InnerStride<1> >)'\n"
      "plugin.cpp:(.text+0x2a1): undefined reference to `student::rk4_step(student::FirstOrderSystem const&, double, "
      "double, Eigen::Ref<Eigen::Matrix<double, -1, 1, 0, -1, 1>, 0, Eigen::InnerStride<1> >)'\n"
      "/usr/bin/ld: plugin.cpp:(.text+0x2f0): undefined reference to `student::midpoint_step(student::FirstOrderSystem "
      "const&, double, double, Eigen::Ref<Eigen::Matrix<double, -1, 1, 0, -1, 1>, 0, Eigen::InnerStride<1> >)'\n"
      "collect2: error: ld returned 1 exit status\n";
  const std::string shown = motus::grade::compiler_messages(linker, ended, limits, 1, handout);
  const std::string first = shown.substr(0, shown.find('\n'));
  EXPECT_EQ(first.rfind("The handout's header declares student::rk4_step, student::midpoint_step, and your files define "
                        "none of them with exactly their parameters",
                        0),
            0u)
      << shown;
  EXPECT_NE(first.find("VectorInOut is Eigen::Ref<Eigen::Matrix<double, -1, 1, ...>>"), std::string::npos) << first;
  EXPECT_EQ(shown.substr(shown.find('\n') + 1), "The compiler said:\n" + linker + "(the compiler exited with status 1)\n");

  // One function: said in the singular.
  const std::string one =
      motus::grade::compiler_messages(linker.substr(0, linker.find("plugin.cpp:(.text+0x2a1)")), ended, limits, 1, handout);
  EXPECT_EQ(one.rfind("The handout's header declares student::rk4_step, and your files define no function of that name "
                      "with exactly its parameters",
                      0),
            0u)
      << one;
  // Nothing more where the name is not the handout's (a helper of the student's own, declared and never
  // defined: another mistake), nor for a variable, nor for a student's own words that only look like the
  // linker's (an #error line begins with a file's line number), nor without the handout's text.
  const auto as_it_was = [&](const std::string& errors, const std::string& text) {
    EXPECT_EQ(motus::grade::compiler_messages(errors, ended, limits, 1, text),
              "The compiler said:\n" + errors + "(the compiler exited with status 1)\n");
  };
  as_it_was("integrators.cpp:(.text+0x10): undefined reference to `student::my_helper(double)'\n", handout);
  as_it_was("integrators.cpp:(.text+0x10): undefined reference to `student::kTable'\n", handout);
  as_it_was("/submission/integrators.cpp:1:2: error: #error x:(.t): undefined reference to `student::rk4_step(\n", handout);
  as_it_was(linker, "");
}

// ---------------------------------------------------------------------------------------------------
// 4. An unknown assignment

// Every other bad input (a missing submission folder, a bad --hidden, limits out of range) leaves
// --results a results.json that says what was wrong; an unknown assignment left none (exit 2), and
// on Gradescope a missing results.json shows every student only "the autograder failed".
TEST(GradeSubmissions, AnUnknownAssignmentStillLeavesAResultsFileThatSaysSo) {
  TempDir dir;
  const fs::path submission = copy_solution(dir, "integrators", "solution");
  const auto r = run_motus(dir, {"grade", "nosuchassignment", submission.string(), "--results", (dir / "r.json").string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("nosuchassignment: no such assignment"), std::string::npos) << r.err;
  ASSERT_TRUE(fs::is_regular_file(dir / "r.json")) << r.err;
  const json result = read_json(dir / "r.json");
  expect_valid_gradescope(result);
  EXPECT_EQ(result["score"], 0);
  EXPECT_NE(result["output"].get<std::string>().find("nosuchassignment: no such assignment"), std::string::npos)
      << result.dump(2);
  // As for the others: a results file there already is not written over without --overwrite.
  write_file(dir / "kept.json", "{}");
  const auto kept = run_motus(dir, {"grade", "nosuchassignment", submission.string(), "--results", (dir / "kept.json").string()});
  EXPECT_EQ(kept.status, 2) << kept.err;
  EXPECT_EQ(read_file(dir / "kept.json"), "{}");
}

}  // namespace
