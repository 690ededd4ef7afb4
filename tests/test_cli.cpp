// The `motus` command as a user meets it: the built binary run through the shell.
//   Bad input (docs/scene-format.md "Errors", docs/cli.md): exit status 2 and exactly one line on standard error,
//   "motus: error: FILE: FIELD: MESSAGE", naming the file, the field path and what is wrong.
//   Good input: every shipped scene runs and `--json` prints the fields docs/cli.md documents.
//   Numbers: the course's Euler table for the spring (tests/reference/integrators.md: m = 10, k = 5, x0 = 20,
//   h = 1 gives x = 20, 20, 10, -10, -35, -55 and v = 0, -10, -20, -25, -20, -2.5 at t = 0..5).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

#include "cli_harness.hpp"
#include "motus/scene_file/spelling.hpp"

namespace {

using namespace motus_test;


// ---------------------------------------------------------------------------------------------------------
// Bad input: one case per row. `file` is the scene's text (written to a temporary file) or, when it starts
// with "@", the name of a shipped scene. The one line of standard error must contain `FILE: FIELD: ` and
// `what`.

struct BadInput {
  const char* name;
  std::string file;
  std::vector<std::string> args;  // after `run SCENE`
  std::string field;
  std::string what;
};

// A small valid mechanical scene with two bodies, to break one field at a time.
std::string two_bodies(const std::string& second_body, const std::string& extra = "") {
  return R"({"dimensions": 1, "bodies": [{"mass": 1, "position": [0]}, )" + second_body +
         R"(], "forces": [{"type": "spring", "a": 0, "b": 1, "stiffness": 1}], "dt": 0.1, "duration": 1)" + extra +
         "}";
}
const std::string kGoodBody = R"({"mass": 2, "position": [1]})";

const std::vector<BadInput> kBadInputs = {
    {"malformed_json", "{\n  \"dimensions\": 1,\n  \"bodies\": [{\"mass\": 1 \"position\": [0]}],\n  \"dt\": 1\n}", {},
     "bodies[0].mass", "malformed JSON at line 3"},
    {"trailing_comma", two_bodies(kGoodBody + ",", ""), {}, "bodies", "malformed JSON"},
    {"nan_literal_in_file", two_bodies(R"({"mass": NaN, "position": [1]})"), {}, "bodies[1].mass",
     "malformed JSON at line 1"},
    {"unknown_body_field", two_bodies(R"({"mass": 2, "position": [1], "velocty": [0]})"), {}, "bodies[1].velocty",
     "unknown field, did you mean velocity? (expected one of: mass, position, velocity, radius, restitution)"},
    {"unknown_top_level_field", two_bodies(kGoodBody, R"(, "exat": "harmonic")"), {}, "exat", "unknown field"},
    {"unknown_force_field", R"({"dimensions": 1, "bodies": [{"mass": 1, "position": [1]}],
        "forces": [{"type": "spring", "a": 0, "anchor": [0], "stiffness": 1, "k": 1}], "dt": 1, "duration": 1})",
     {}, "forces[0].k", "unknown field"},
    {"unknown_parameter", R"({"system": {"type": "lorenz", "parameters": {"sigmaa": 10}, "initial": [1, 1, 1]},
        "dt": 0.01, "duration": 1})",
     {}, "system.parameters.sigmaa", "unknown field, did you mean sigma? (expected one of: sigma, rho, beta)"},
    {"equations_unknown_variable", R"({"system": {"type": "equations", "variables": ["x", "v"],
        "equations": {"x": "v", "v": "-k*x"}, "initial": [1, 0]}, "dt": 0.1, "duration": 1})",
     {}, "system.equations.v", "unknown variable \"k\" at column 2"},
    {"equations_syntax_error", R"({"system": {"type": "equations", "variables": ["x", "v"],
        "equations": {"x": "v", "v": "-x +* v"}, "initial": [1, 0]}, "dt": 0.1, "duration": 1})",
     {}, "system.equations.v", "syntax error at column 5"},
    {"equations_missing_equation", R"({"system": {"type": "equations", "variables": ["x", "v"],
        "equations": {"x": "v"}, "initial": [1, 0]}, "dt": 0.1, "duration": 1})",
     {}, "system.equations.v", "missing: every variable needs its equation"},
    {"equations_extra_equation", R"({"system": {"type": "equations", "variables": ["x"],
        "equations": {"x": "1", "y": "2"}, "initial": [1]}, "dt": 0.1, "duration": 1})",
     {}, "system.equations.y", "no variable is called \"y\""},
    {"equations_bad_expression_via_set", "@van_der_pol", {"--set", "system.equations.v=mu*(1 - x^2*v - x"},
     "system.equations.v", "syntax error at column"},
    {"missing_mass", two_bodies(R"({"position": [1]})"), {}, "bodies[1].mass", "missing (required)"},
    {"missing_dt", R"({"dimensions": 1, "bodies": [{"mass": 1, "position": [1]}], "duration": 1})", {}, "dt",
     "missing (required)"},
    {"missing_bodies_and_system", R"({"dt": 1, "duration": 1})", {}, "bodies", "missing"},
    {"wrong_type_mass", two_bodies(R"({"mass": "2", "position": [1]})"), {}, "bodies[1].mass",
     "must be a number, not a string"},
    {"wrong_type_position", two_bodies(R"({"mass": 2, "position": 1})"), {}, "bodies[1].position",
     "must be an array of numbers, not a number"},
    {"wrong_length_position", two_bodies(R"({"mass": 2, "position": [1, 2]})"), {}, "bodies[1].position",
     "must have 1 number (got 2)"},
    {"zero_mass", two_bodies(R"({"mass": 0, "position": [1]})"), {}, "bodies[1].mass", "must be > 0"},
    {"negative_mass", two_bodies(R"({"mass": -1, "position": [1]})"), {}, "bodies[1].mass", "must be > 0"},
    {"zero_dt", R"({"dimensions": 1, "bodies": [{"mass": 1, "position": [1]}], "dt": 0, "duration": 1})", {}, "dt",
     "must be > 0"},
    {"negative_dt", R"({"dimensions": 1, "bodies": [{"mass": 1, "position": [1]}], "dt": -0.5, "duration": 1})", {},
     "dt", "must be > 0"},
    {"infinite_number_in_file", two_bodies(R"({"mass": 1e999, "position": [1]})"), {}, "bodies[1].mass",
     "numbers must be finite"},
    {"nan_via_set", "@spring", {"--set", "bodies[0].mass=NaN"}, "bodies[0].mass",
     "must be a finite number (got NaN)"},
    {"infinity_via_set", "@spring", {"--set", "dt=inf"}, "dt", "must be a finite number (got inf)"},
    {"zero_mass_via_set", "@spring", {"--set", "bodies[0].mass=0"}, "bodies[0].mass", "must be > 0"},
    {"unknown_integrator_in_file", two_bodies(kGoodBody, R"(, "integrator": "rk5")"), {}, "integrator",
     "unknown integrator \"rk5\""},
    {"unknown_integrator_option", "@spring", {"--integrator", "rk5"}, "--integrator", "unknown integrator \"rk5\""},
    {"symplectic_on_system_in_file", R"({"system": {"type": "lorenz", "initial": [1, 1, 1]},
        "integrator": "velocity-verlet", "dt": 0.01, "duration": 1})",
     {}, "integrator", "velocity-verlet is symplectic"},
    {"symplectic_on_system_option", "@lorenz", {"--integrator", "verlet"}, "--integrator", "verlet is symplectic"},
    {"spring_with_b_and_anchor", R"({"dimensions": 1, "bodies": [{"mass": 1, "position": [1]}, {"mass": 1, "position": [2]}],
        "forces": [{"type": "spring", "a": 0, "b": 1, "anchor": [0], "stiffness": 1}], "dt": 1, "duration": 1})",
     {}, "forces[0].b", "exactly one of"},
    {"pendulum_in_2d", R"({"dimensions": 2, "bodies": [{"mass": 1, "position": [0, 0]}],
        "forces": [{"type": "pendulum", "length": 1}], "dt": 1, "duration": 1})",
     {}, "forces[0].type", "1-D"},
    {"exact_that_does_not_fit", "@spring", {"--set", "exact=kepler"}, "exact", "\"kepler\" needs"},
    // The closed forms know forces alone: with a floor, a pin or two balls the "error" was the closed form's
    // (a projectile bouncing off a floor read 69 m from projectile-drag's answer).
    {"exact_with_a_floor", "@projectile_drag", {"--set", R"(colliders=[{"type": "plane", "normal": [0, 1]}])"}, "exact",
     "\"projectile-drag\" solves forces alone, and the scene has colliders"},
    {"exact_with_a_pin", "@oscillator", {"--set", R"(pins=[{"body": 0}])"}, "exact",
     "\"harmonic\" solves forces alone, and the scene has pins"},
    {"set_index_out_of_range", "@spring", {"--set", "bodies[3].mass=1"}, "bodies",
     "has 1 entry, so bodies[3].mass cannot be set"},
    {"set_bad_index", "@spring", {"--set", "bodies[x].mass=1"}, "bodies[x].mass", "bad index"},
    {"set_through_a_number", "@spring", {"--set", "dt.x=1"}, "dt", "is not an object"},
    {"set_without_value", "@spring", {"--set", "bodies[0].mass"}, "bodies[0].mass", "needs PATH=VALUE"},
    {"set_unknown_field", "@spring", {"--set", "bodies[0].mas=1"}, "bodies[0].mas", "unknown field"},
    // (The known fields whole: shortened in the middle at 240 bytes, the list lost the very ones meant.)
    {"set_unknown_top_level_field", "@spring", {"--set", "walls=[]"}, "walls",
     "unknown field (expected one of: $schema, name, description, system, bodies, dimensions, lattice, cloth, rope, "
     "forces, colliders, sticks, pins, constraint_iterations, constraint_substeps, integrator, dt, duration, "
     "start_time, rtol, atol, output_interval, exact, reference)"},
    // (".dt" and "bodies[0]mass" were taken as dt and bodies[0].mass; 1e309 as the word "1e309".)
    {"set_leading_dot", "@spring", {"--set", ".dt=1"}, ".dt", "empty field name"},
    {"set_name_right_after_index", "@spring", {"--set", "bodies[0]mass=4"}, "bodies[0]mass",
     "a '.' must come between an index and a field name"},
    {"set_number_overflow", "@spring", {"--set", "dt=1e309"}, "dt", "number overflow: 1e309 (numbers must be finite)"},
    // A name or description with an escape sequence would rewrite the terminal it is printed on.
    {"escape_in_name", "@spring", {"--set", "name=sp\x1b[2Jring"}, "name", "has a control character (code 27)"},
    {"escape_in_description", "@spring", {"--set", "description=a\rcarriage return"}, "description",
     "has a control character (code 13)"},
    {"c1_control_in_name", "@spring", {"--set", "name=c1\xc2\x9b" "2J"}, "name", "has a control character (U+009B)"},
    // Two reference states at one time: bench precision measured against whichever it read.
    {"reference_time_twice", "@lorenz", {"--set", "reference[1].t=1"}, "reference[1].t",
     "reference[0] has this time too"},
};

void PrintTo(const BadInput& c, std::ostream* os) { *os << c.name; }

class BadInputTest : public ::testing::TestWithParam<BadInput> {};

TEST_P(BadInputTest, ExitsTwoWithOneLineNamingFileAndField) {
  const BadInput& c = GetParam();
  TempDir dir;
  std::string file;
  if (c.file.rfind('@', 0) == 0) {
    file = scene(c.file.substr(1));
  } else {
    file = (dir / "bad_scene.json").string();
    write_file(file, c.file);
  }
  std::vector<std::string> args = {"run", file};
  args.insert(args.end(), c.args.begin(), c.args.end());
  const Result r = run_motus(dir, args);

  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << "stderr:\n" << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  const std::string expected_prefix = "motus: error: " + file + ": " + c.field + ": ";
  EXPECT_EQ(r.err.rfind(expected_prefix, 0), 0u) << "expected to start with: " << expected_prefix << "\nstderr: " << r.err;
  EXPECT_NE(r.err.find(c.what), std::string::npos) << "expected: " << c.what << "\nstderr: " << r.err;
}

INSTANTIATE_TEST_SUITE_P(Cli, BadInputTest, ::testing::ValuesIn(kBadInputs),
                         [](const auto& info) { return std::string(info.param.name); });

// Numbers a double holds, but whose differences it does not: bodies ±9e307 m apart (the grid's
// size came out NaN, and a vector "larger than max_size()" was all it said), and a --duration
// past the scene's for stress (its help says it is at most the scene's; the file's dt was blamed).
TEST(CliErrors, ExtremeButFiniteNumbersEndInAMessageThatSaysWhat) {
  TempDir dir;
  // (At rest: moving, at 1 m/s where doubles are 2e292 m apart, the scene is refused before it runs,
  // by check_position_resolution.)
  const Result apart = run_motus(dir, {"run", scene("head_on"), "--set", "bodies[0].position=[-9e307,0]", "--set",
                                       "bodies[1].position=[9e307,0]", "--set", "bodies[0].velocity=[0,0]", "--set",
                                       "bodies[1].velocity=[0,0]", "--set", "exact="});
  EXPECT_EQ(apart.status, 1) << apart.err;
  EXPECT_EQ(count_lines(apart.err), 1) << apart.err;
  EXPECT_NE(apart.err.find("too far apart for the collision grid"), std::string::npos) << apart.err;
  const Result moving = run_motus(dir, {"run", scene("head_on"), "--set", "bodies[0].position=[-9e307,0]", "--set",
                                        "bodies[1].position=[9e307,0]", "--set", "exact="});
  EXPECT_EQ(moving.status, 2) << moving.err;
  EXPECT_NE(moving.err.find("head_on.json: bodies[0].position: at 9e+307 m positions are"), std::string::npos)
      << moving.err;
  const Result stress = run_motus(dir, {"stress", scene("oscillator"), "--out", (dir / "stress").string(), "--steps", "100",
                                        "--drift-steps", "100", "--duration", "1e308", "--integrators", "euler"});
  EXPECT_EQ(stress.status, 0) << stress.err;
}

// A run whose equation leaves its functions' domain stops with exit 1 naming the equation, where
// it went and from what state (it blamed the step: "the integrator is unstable at this step"); a
// run that blows up at too large a step still blames the step.
TEST(CliErrors, AnEquationThatGivesNaNIsNamedWhenTheStateIsNoLongerFinite) {
  TempDir dir;
  write_file(dir / "domain.json", R"j({"system": {"type": "equations", "variables": ["x", "v"],
      "equations": {"x": "v", "v": "sqrt(x - 2)"}, "initial": [1, 0.5]}, "dt": 0.1, "duration": 1})j");
  const Result domain = run_motus(dir, {"run", (dir / "domain.json").string()});
  EXPECT_EQ(domain.status, 1) << domain.err;
  EXPECT_EQ(count_lines(domain.err), 1) << domain.err;
  EXPECT_NE(domain.err.find("the equation v' = sqrt(x - 2) gave nan at t = 0 where x = 1, v = 0.5"), std::string::npos)
      << domain.err;
  // An adaptive integrator rejects the step and stops there, saying the same (it said "an error
  // estimate that is not finite?", at "t = 0.000000").
  const Result adaptive = run_motus(dir, {"run", (dir / "domain.json").string(), "--integrator", "rk45"});
  EXPECT_EQ(adaptive.status, 1) << adaptive.err;
  EXPECT_EQ(count_lines(adaptive.err), 1) << adaptive.err;
  EXPECT_NE(adaptive.err.find("rejected step at t = 0 (the equation v' = sqrt(x - 2) gave nan at t = 0 where x = 1, v = 0.5"),
            std::string::npos)
      << adaptive.err;
  const Result unstable = run_motus(dir, {"run", scene("lorenz_equations"), "--dt", "0.5", "--steps", "20"});
  EXPECT_EQ(unstable.status, 1) << unstable.err;
  EXPECT_NE(unstable.err.find("the integrator is unstable at this step"), std::string::npos) << unstable.err;
}

// A run whose sticks' lengths stop being numbers (the rope under g = 1e300 m/s² blows up) says its
// largest stick-length error is inf, as `motus compare`'s constraint column says it (it said "nan
// over the run, -nan at the end": kept as NaN, and printed with its meaningless sign).
TEST(CliErrors, ARunThatBlewUpSaysItsStickErrorIsInfAsCompareDoes) {
  TempDir dir;
  const Result r = run_motus(dir, {"run", scene("rope"), "--set", "forces[0].g=[0,-1e300]", "--steps", "50"});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.out.find("constraints  largest stick-length error inf over the run, nan at the end"), std::string::npos) << r.out;
}

// A small state is looked at after every step: "no longer finite by t" is the first row of the
// trajectory that is not finite (the oscillator's explicit Euler at dt = 10: its amplitude grows by
// √101 a step and passes the largest double in step 308; the look every 16 steps said t = 3200). A
// student's spring that gave NaN from t = 1 read "by t = 5". Found by an audit.
TEST(CliErrors, ASmallStateNoLongerFiniteIsNamedAtItsFirstStep) {
  TempDir dir;
  const Result r = run_motus(dir, {"run", "oscillator", "--integrator", "euler", "--dt", "10", "--steps", "2000", "--repeats",
                                   "1", "--trajectory", (dir / "t.csv").string()});
  EXPECT_EQ(r.status, 1) << r.err;
  std::istringstream csv(read_file(dir / "t.csv"));
  std::string row, first_not_finite;
  std::getline(csv, row);
  ASSERT_EQ(row.rfind("t,x0,vx0,", 0), 0u) << row;  // the state's two columns (the energies after them overflow sooner)
  while (first_not_finite.empty() && std::getline(csv, row)) {
    const std::string state = row.substr(0, row.find(',', row.find(',', row.find(',') + 1) + 1));
    if (state.find("inf") != std::string::npos || state.find("nan") != std::string::npos) first_not_finite = row.substr(0, row.find(','));
  }
  ASSERT_EQ(first_not_finite, "3080");
  EXPECT_NE(r.err.find("the state was no longer finite by t = 3080 (the integrator is unstable"), std::string::npos) << r.err;
}

TEST(CliErrors, MissingFileIsOneLineExitTwo) {
  TempDir dir;
  const std::string file = (dir / "no_such_scene.json").string();
  const Result r = run_motus(dir, {"run", file});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err, "motus: error: " + file + ": no such file (motus list shows the scenes)\n");
}

TEST(CliErrors, BadOptionValueIsOneLineExitTwo) {
  TempDir dir;
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", scene("spring"), "--dt", "abc"},
        std::vector<std::string>{"run", scene("spring"), "--no-such-option"},
        std::vector<std::string>{"run", scene("spring"), "--steps", "3", "--duration", "2"},
        std::vector<std::string>{"run", scene("spring"), "--dt", "0"},
        std::vector<std::string>{"run", scene("spring"), "--steps", "0"},
        // steps·dt past a double: it was reported as --duration, which was not given
        std::vector<std::string>{"run", scene("spring"), "--dt", "1e308", "--steps", "2"},
        // a video at a frame rate ffmpeg refuses: refused before a frame is drawn (they were all
        // drawn, then deleted with the failed run's folder)
        std::vector<std::string>{"render", scene("oscillator"), "--out", (dir / "frames").string(), "--duration", "0.5",
                                 "--fps", "1e-20", "--video", "gif"},
        // a GIF faster than its hundredths of a second: it played at 10 frames a second, without a word
        std::vector<std::string>{"render", scene("oscillator"), "--out", (dir / "frames").string(), "--duration", "0.1",
                                 "--fps", "10000", "--video", "gif"},
        // compare's --fps draws nothing without --render: it was taken and ignored without a word
        std::vector<std::string>{"compare", scene("head_on"), "--out", (dir / "frames").string(), "--fps", "10"}}) {
    const Result r = run_motus(dir, args);
    EXPECT_EQ(r.status, 2) << args.back() << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << args.back() << ": " << r.err;
    EXPECT_EQ(r.err.rfind("motus: error: ", 0), 0u) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "frames"));
  // A word that is no command was "A subcommand is required", as if none had been given.
  EXPECT_EQ(run_motus(dir, {"rnu", scene("spring")}).err,
            "motus: error: unknown command \"rnu\", did you mean run? (the commands: run, compare, list, bench, render, "
            "grade, stress; motus --help)\n");
  EXPECT_EQ(run_motus(dir, {"run", scene("spring"), "--dt", "1e308", "--steps", "2"}).err,
            "motus: error: --steps: 2 steps of 1e+308 s is more time than a double holds\n");
  // Past 4.5e9 to 9e9 steps from t = 0 (by dt) their times are not told apart: the advice was
  // "a larger dt or a shorter duration", neither of which a --steps run can use (found by fuzzing).
  // It says how many: at dt = 1 the times up to 2^33 are 2^-20 ≤ 1e-6 apart, past it 2^-19 (an
  // audit found "about 4.5e9 at most" while 8.5e9 ran).
  auto as_3g = [](double x) {  // (as fmt's {:.3g} prints it)
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", x);
    return std::string(text);
  };
  const Result many = run_motus(dir, {"run", scene("spring"), "--steps", "9000000000"});
  EXPECT_EQ(many.status, 2);
  EXPECT_NE(many.err.find("--steps: at t = 9e+09 times are 1.90735e-06 apart, too coarse for steps of 1 (fewer steps: "
                          "from t = 0, at most " + as_3g(std::ldexp(1.0, 33) - 1) + " of 1)"),
            std::string::npos) << many.err;
  const Result tenth = run_motus(dir, {"run", scene("spring"), "--steps", "6000000000", "--set", "dt=0.1"});
  EXPECT_EQ(tenth.status, 2);  // at dt = 0.1: 2^-24 ≤ 1e-7 < 2^-23, the times told apart up to 2^29 s
  EXPECT_NE(tenth.err.find("at most " + as_3g(std::ceil(std::ldexp(1.0, 29) / 0.1) - 1) + " of 0.1)"),
            std::string::npos) << tenth.err;
  // A subnormal dt: near t = 0 doubles are denorm_min (4.9e-324) apart, more than a millionth of it, and no
  // count of steps holds: it said "at most -1 of 9.99989e-321" (a fuzzing audit). dt from 1e6·denorm_min.
  const Result tiny = run_motus(dir, {"run", scene("spring"), "--dt", "1e-320", "--steps", "20"});
  EXPECT_EQ(tiny.status, 2);
  EXPECT_NE(tiny.err.find("(no count of steps that small can be told apart: dt must be at least " +
                          as_3g(1e6 * std::numeric_limits<double>::denorm_min()) + ")"),
            std::string::npos) << tiny.err;
  // An empty number ran with the scene's own, exit 0 (found by fuzzing the options).
  for (const auto& [command, option] : std::vector<std::pair<std::string, std::string>>{
           {"run", "--dt"}, {"run", "--duration"}, {"run", "--rtol"}, {"run", "--atol"}, {"compare", "--dt"},
           {"compare", "--duration"}, {"render", "--duration"}, {"bench", "--duration"}}) {
    std::vector<std::string> args = {command, scene("oscillator"), option, "", "--out", (dir / "empty").string()};
    if (command == "run") args.resize(4);
    if (command == "bench") args.insert(args.begin() + 1, "precision");
    const Result r = run_motus(dir, args);
    EXPECT_EQ(r.status, 2) << command << " " << option << ": " << r.err;
    EXPECT_EQ(r.err.rfind("motus: error: " + option + ": \"\" is not a number", 0), 0u) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "empty"));
  // Blanks around a number are dropped on both sides alike: " 0.5" was read and "0.5 " refused.
  for (const std::string dt : {" 0.5", "0.5 ", " 0.5\t"}) {
    const Result r = run_motus(dir, {"run", scene("spring"), "--dt", dt, "--duration", "1", "--json"});
    ASSERT_EQ(r.status, 0) << "\"" << dt << "\": " << r.err;
    EXPECT_EQ(nlohmann::json::parse(r.out).at("steps").get<long>(), 2) << "\"" << dt << "\"";
  }
}

// The known word a misspelt one most likely is: one slip of the fingers (a letter added, dropped, changed, or
// two neighbours swapped) in a short word, more in a longer one; nothing when none is that close.
TEST(Spelling, TheClosestKnownWordIsASlipAwayOrNothing) {
  const std::vector<std::string> integrators = {"euler", "midpoint", "rk4", "rk45", "symplectic-euler", "verlet"};
  EXPECT_EQ(motus::closest_known("eular", integrators), "euler");           // one letter changed
  EXPECT_EQ(motus::closest_known("eluer", integrators), "euler");           // two neighbours swapped: one slip
  EXPECT_EQ(motus::closest_known("Euler", integrators), "euler");           // the case alone
  EXPECT_EQ(motus::closest_known("rk44", integrators), "rk4");              // rk4 and rk45 one away: the first
  EXPECT_EQ(motus::closest_known("symplectc-eulr", integrators), "symplectic-euler");  // two in a long word
  EXPECT_EQ(motus::closest_known("euler", integrators), std::nullopt);      // known
  EXPECT_EQ(motus::closest_known("leapfrog", integrators), std::nullopt);   // no slip of any
  EXPECT_EQ(motus::closest_known("rk", integrators), "rk4");                // one dropped from a short word
  EXPECT_EQ(motus::closest_known("k", integrators), std::nullopt);          // one letter: no guess
  EXPECT_EQ(motus::closest_known("--dtt", {"--dt", "--duration"}), "--dt");  // the dashes are not the name
  EXPECT_EQ(motus::closest_known("-v", {"-h", "--help", "--version"}), std::nullopt);
  EXPECT_EQ(motus::closest_known(std::string(100, 'e'), integrators), std::nullopt);  // no slip, and no work on it
  EXPECT_EQ(motus::did_you_mean("vrlet", integrators), ", did you mean verlet?");
  EXPECT_EQ(motus::did_you_mean("zzz", integrators), "");
  EXPECT_EQ(motus::unknown_one_of("integrator", "vrlet", {"euler", "verlet"}),
            "unknown integrator \"vrlet\", did you mean verlet? (known: euler, verlet)");
  EXPECT_EQ(motus::unknown_one_of("peer", "havok", {"odeint", "box2d"}), "unknown peer \"havok\" (known: odeint, box2d)");
}

// The command line's mistakes, in motus's words: the option or command named as given, the word most likely
// meant, and the help to read. (They were CLI11's: "The following arguments were not expected: 1 --dtt" — the
// value blamed, the order reversed — "A subcommand is required" for `motus --hlep` or `motus bench precison`,
// "Could not convert: --dt = abc", "--dt: At Most 1 required but received 2", "--OUT is required" of a
// misspelt --out.)
TEST(CliErrors, TheCommandLinesMistakesAreNamedWithTheWordMostLikelyMeant) {
  TempDir dir;
  const std::string spring = scene("spring");
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"run", spring, "--dtt", "1"}, "unknown option --dtt, did you mean --dt? (motus run --help)"},
      {{"run", spring, "--dtt=1"}, "unknown option --dtt, did you mean --dt? (motus run --help)"},
      {{"render", spring, "--ot", "x"}, "unknown option --ot, did you mean --out? (motus render --help)"},
      {{"stress", spring, "--repeats", "2"}, "unknown option --repeats (motus stress --help)"},
      {{"--hlep"}, "unknown option --hlep, did you mean --help? (a command's options come after it: motus COMMAND --help)"},
      {{"-v"}, "unknown option -v (a command's options come after it: motus COMMAND --help)"},
      {{"bench", "precison", spring},
       "bench: unknown command \"precison\", did you mean precision? (the commands: precision; motus bench --help)"},
      {{"bench"}, "bench: a command is needed (the commands: precision; motus bench --help)"},
      {{"run", spring, "--dt", "abc"}, "--dt: \"abc\" is not a number (motus run --help)"},
      {{"run", spring, "--dt", "1", "--dt", "2"}, "--dt: given more than once (motus run --help)"},
      {{"run", spring, "--steps", "3", "--duration", "2"}, "--duration and --steps cannot be given together (motus run --help)"},
      {{"compare", spring, "--fps", "10"}, "--fps: only with --render (motus compare --help)"},
      {{"run"}, "SCENE is missing (motus run --help)"},
      {{"run", spring, "extra"}, "unexpected argument \"extra\" (motus run --help)"},
      // an option with no value took the next option as its own, and only the word left over was named (a fuzzing audit)
      {{"run", spring, "--integrator", "--steps", "20"},
       "--integrator: needs a value; the option --steps after it was taken as one (motus run --help)"},
      {{"compare", spring, "--out", "--duration", "1"},
       "--out: needs a value; the option --duration after it was taken as one (motus compare --help)"},
      // after "--" every word is an argument: an option there is a word too many (it said "unknown option --")
      {{"run", "--", spring, "--repeats", "1"},
       "unexpected argument \"--repeats\" after --, where every word is an argument (options go before --) (motus run --help)"},
      {{"render", spring, "--out", (dir / "frames").string(), "--video", "mp5"},
       "--video: \"mp5\" is none of mp4, gif, did you mean mp4? (motus render --help)"},
      {{"compare", spring, "--engines", "motus,box2"},
       "--engines: unknown engine \"box2\", did you mean box2d? (known: motus, box2d, bullet)"},
      {{"bench", "precision", spring, "--peers", "odient"},
       "--peers: unknown peer \"odient\", did you mean odeint? (known: odeint, box2d, bullet)"},
      // options that would be taken and change nothing
      {{"run", spring, "--overwrite"}, "--overwrite: only with --trajectory (motus run --help)"},
      {{"bench", "precision", spring, "--overwrite"}, "--overwrite: only with --csv (motus bench precision --help)"},
      {{"run", spring, "--rtol", "1e-3"},
       "--rtol: euler takes fixed steps and no tolerance (rk45, dop853 and rk4-doubling take one)"},
      {{"run", "sprng"}, "sprng: no such file, nor a shipped scene of that name, did you mean spring? (motus list shows "
                         "the scenes)"},
      {{"stress", spring, "--integrators", "eluer"},
       "--integrators: unknown integrator \"eluer\", did you mean euler? (known: euler, midpoint, rk4, rk4-doubling, "
       "rk45, dop853, symplectic-euler, symplectic-euler-x, verlet, velocity-verlet, yoshida4)"},
  };
  for (const auto& [args, line] : cases) {
    const Result r = run_motus(dir, args);
    EXPECT_EQ(r.status, 2) << args.back();
    EXPECT_EQ(r.err, "motus: error: " + line + "\n") << args.back();
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  // `motus help [COMMAND]` is `motus [COMMAND] --help`; `motus` alone shows the commands, and fails (nothing done).
  const Result help_run = run_motus(dir, {"help", "run"});
  EXPECT_EQ(help_run.status, 0);
  EXPECT_EQ(help_run.out, run_motus(dir, {"run", "--help"}).out);
  EXPECT_NE(help_run.out.find("--dt"), std::string::npos) << help_run.out;
  const Result help_help = run_motus(dir, {"help", "help"});  // (it said: unknown command "help")
  EXPECT_EQ(help_help.status, 0) << help_help.err;
  EXPECT_EQ(help_help.out, run_motus(dir, {"--help"}).out);
  // A word after the command asked about, or after --version, was passed over in silence, exit 0
  // (found by fuzzing the options); a command spelt wrong is still told what was meant.
  EXPECT_EQ(run_motus(dir, {"help", "run", "extra"}).err,
            "motus: error: help: \"extra\" is not a command of motus run (motus help run)\n");
  EXPECT_EQ(run_motus(dir, {"help", "bench", "precision", "extra"}).status, 2);
  EXPECT_NE(run_motus(dir, {"help", "bench", "precison"}).err.find("did you mean precision?"), std::string::npos);
  const Result version = run_motus(dir, {"--version", "bogus"});
  EXPECT_EQ(version.status, 2);
  EXPECT_EQ(version.err, "motus: error: --version: takes nothing after it (got \"bogus\")\n");
  EXPECT_TRUE(version.out.empty()) << version.out;
  const Result bare = run_motus(dir, {});
  EXPECT_EQ(bare.status, 2);
  EXPECT_TRUE(bare.out.empty()) << bare.out;
  EXPECT_NE(bare.err.find("compare"), std::string::npos) << bare.err;
  EXPECT_NE(bare.err.find("motus: error: a command is needed"), std::string::npos) << bare.err;
}

// Help fits a terminal: descriptions wrapped at words under their column (lines ran to 275 characters, which
// a terminal broke anywhere), to 100 columns when standard output is no terminal, none of their words lost.
TEST(CliHelp, EveryCommandsHelpFitsInAHundredColumnsWhenPiped) {
  TempDir dir;
  auto columns = [](const std::string& line) {
    return std::count_if(line.begin(), line.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; });
  };
  for (const std::vector<std::string>& command :
       {std::vector<std::string>{}, {"run"}, {"compare"}, {"list"}, {"bench"}, {"bench", "precision"}, {"render"},
        {"grade"}, {"stress"}}) {
    std::vector<std::string> args = command;
    args.push_back("--help");
    const Result r = run_motus(dir, args);
    EXPECT_EQ(r.status, 0) << r.err;
    std::istringstream lines(r.out);
    int count = 0;
    for (std::string line; std::getline(lines, line); ++count) EXPECT_LE(columns(line), 100) << line;
    EXPECT_GT(count, 3) << r.out;
  }
  // A long description's words, all there, in order: compare's --size.
  const Result compare = run_motus(dir, {"compare", "--help"});
  std::string words;
  std::istringstream text(compare.out);
  for (std::string w; text >> w;) words += w + " ";
  EXPECT_NE(words.find("The size of each engine's panel in the pictures (the report's first and last frames; every "
                       "frame with --render)"),
            std::string::npos)
      << compare.out;
}

// ---------------------------------------------------------------------------------------------------------
// Good input.

std::vector<fs::path> shipped_scenes() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kScenes))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

void expect_number(const nlohmann::json& j, const std::string& what) {
  EXPECT_TRUE(j.is_number()) << what << " is " << j.dump();
}

void expect_numbers(const nlohmann::json& j, const std::string& what) {
  ASSERT_TRUE(j.is_array()) << what << " is " << j.dump();
  for (const auto& x : j) EXPECT_TRUE(x.is_number()) << what << " is " << j.dump();
}

TEST(CliRun, EveryShippedSceneRunsAndPrintsTheDocumentedJson) {
  TempDir dir;
  const auto scenes = shipped_scenes();
  ASSERT_GE(scenes.size(), 12u);  // the twelve scenes of docs/scene-format.md
  for (const auto& file : scenes) {
    SCOPED_TRACE(file.string());
    const Result r = run_motus(dir, {"run", file.string(), "--json"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    const auto j = nlohmann::json::parse(r.out, nullptr, /*allow_exceptions=*/false);
    ASSERT_FALSE(j.is_discarded()) << r.out;
    ASSERT_TRUE(j.is_object());

    EXPECT_EQ(j.at("scene"), file.stem().string());
    EXPECT_TRUE(j.at("file").is_string());
    EXPECT_TRUE(j.at("integrator").is_string());
    for (const char* key : {"dt", "t", "wall_seconds"}) expect_number(j.at(key), key);
    for (const char* key : {"steps", "rejected", "evaluations"}) EXPECT_TRUE(j.at(key).is_number_integer()) << key;
    EXPECT_GT(j.at("steps").get<long>(), 0);
    const auto scene_json = nlohmann::json::parse(read_file(file));
    // Every step evaluates the forces at least once — and a scene without forces never
    // does (the world runs only the passes a scene needs). Verlet with its positions projected
    // takes a uniform gravity alone once, at its start: it never changes (cli.md, evaluations).
    const auto forces = scene_json.value("forces", nlohmann::json::array());
    const bool projected_under_gravity_alone =
        scene_json.value("integrator", "") == "verlet" && !forces.empty() &&
        std::all_of(forces.begin(), forces.end(), [](const nlohmann::json& f) { return f.value("type", "") == "gravity"; }) &&
        (scene_json.contains("sticks") || scene_json.contains("pins") || scene_json.contains("ragdoll") ||
         scene_json.contains("cloth") || scene_json.contains("rope"));
    if (projected_under_gravity_alone)
      EXPECT_EQ(j.at("evaluations").get<long>(), 1);
    else if (scene_json.contains("system") || !forces.empty())
      EXPECT_GE(j.at("evaluations").get<long>(), j.at("steps").get<long>());
    else
      EXPECT_EQ(j.at("evaluations").get<long>(), 0);

    const double end = scene_json.value("start_time", 0.0) + scene_json.at("duration").get<double>();
    EXPECT_GE(j.at("t").get<double>(), end - 1e-9 * std::max(1.0, std::abs(end)));
    EXPECT_LT(j.at("t").get<double>(), end + j.at("dt").get<double>());

    if (!scene_json.contains("system")) {
      for (const char* when : {"initial", "final"}) {
        for (const char* part : {"kinetic", "potential", "total"})
          expect_number(j.at("energy").at(when).at(part), std::string("energy.") + when + "." + part);
        expect_numbers(j.at("momentum").at(when), std::string("momentum.") + when);
      }
      // Listed bodies, and those a generator (lattice, cloth, rope) adds after them.
      const size_t listed = scene_json.value("bodies", nlohmann::json::array()).size();
      const bool generated = scene_json.contains("lattice") || scene_json.contains("cloth") || scene_json.contains("rope");
      const size_t bodies = j.at("state").at("x").size(), d = scene_json.at("dimensions").get<size_t>();
      if (generated)
        EXPECT_GT(bodies, listed);
      else
        EXPECT_EQ(bodies, listed);
      ASSERT_EQ(j.at("state").at("v").size(), bodies);
      for (size_t i = 0; i < bodies; ++i) {
        EXPECT_EQ(j.at("state").at("x")[i].size(), d);
        EXPECT_EQ(j.at("state").at("v")[i].size(), d);
      }
      EXPECT_EQ(j.at("momentum").at("final").size(), d);
    } else {
      EXPECT_TRUE(j.at("energy").is_null());
      EXPECT_TRUE(j.at("momentum").is_null());
      EXPECT_TRUE(j.at("angular_momentum").is_null());
      expect_numbers(j.at("state").at("y"), "state.y");
      EXPECT_EQ(j.at("state").at("y").size(), scene_json.at("system").at("initial").size());
      EXPECT_EQ(j.at("state").at("names").size(), j.at("state").at("y").size());
    }
  }
}

// The course's table (tests/reference/integrators.md): explicit Euler, h = 1, t = 5: x = −55, v = −2.5.
TEST(CliRun, SpringJsonMatchesTheNotesEulerTableAtFive) {
  TempDir dir;
  const Result r = run_motus(dir, {"run", scene("spring"), "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("integrator"), "euler");
  EXPECT_EQ(j.at("t").get<double>(), 5.0);
  EXPECT_EQ(j.at("steps").get<long>(), 5);
  EXPECT_EQ(j.at("state").at("x")[0][0].get<double>(), -55.0);
  EXPECT_EQ(j.at("state").at("v")[0][0].get<double>(), -2.5);
  // Energies of that state: ½ m v² = ½·10·6.25, ½ k x² = ½·5·3025; at the start ½·5·400.
  EXPECT_EQ(j.at("energy").at("final").at("kinetic").get<double>(), 31.25);
  EXPECT_EQ(j.at("energy").at("final").at("potential").get<double>(), 7562.5);
  EXPECT_EQ(j.at("energy").at("initial").at("total").get<double>(), 1000.0);
}

// The same table at t = 3: x = −10, v = −25.
TEST(CliRun, StepsThreeEndsAtThreeOnTheNotesTable) {
  TempDir dir;
  const Result r = run_motus(dir, {"run", scene("spring"), "--steps", "3", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("t").get<double>(), 3.0);
  EXPECT_EQ(j.at("steps").get<long>(), 3);
  EXPECT_EQ(j.at("state").at("x")[0][0].get<double>(), -10.0);
  EXPECT_EQ(j.at("state").at("v")[0][0].get<double>(), -25.0);
}

// Found by fuzzing the options: a count written with a leading zero was read as octal — `--steps
// 010` ran 8 steps, exit 0, and `--repeats 08` was refused as not a whole number. A count is decimal.
TEST(CliRun, ACountWithALeadingZeroIsDecimal) {
  TempDir dir;
  const Result r = run_motus(dir, {"run", scene("spring"), "--steps", "010", "--repeats", "08", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("steps").get<long>(), 10);
  EXPECT_EQ(j.at("t").get<double>(), 10.0);
}

// The step-by-step table parts every two numbers by a space, however long: the stick pendulum's
// bob has vx = -0.00083536552 at its second step, which at 8 digits fills a column's 14.
TEST(CliRun, TheStepTableKeepsItsColumnsApart) {
  TempDir dir;
  const Result r = run_motus(dir, {"run", scene("stick_pendulum"), "--steps", "3", "--repeats", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::stringstream lines(r.out);
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.find("-9.81") == std::string::npos) continue;  // the table's rows: ay = -9.81
    ++rows;
    std::stringstream cells(line);
    int columns = 0;
    for (std::string cell; cells >> cell;) {
      ++columns;
      EXPECT_NO_THROW((void)std::stod(cell)) << cell;
    }
    EXPECT_EQ(columns, 13) << line;  // t and x, v, a of two bodies in 2-D
  }
  EXPECT_EQ(rows, 4) << r.out;
}

// The step table's times, and the start on the time line, tell every step apart: a start at 1 with
// dt = 1e-7 printed "1" six times (six figures), and a start of 1234.56789 as 1234.57.
TEST(CliRun, TheStepTableTellsItsTimesApart) {
  TempDir dir;
  const Result r = run_motus(dir, {"run", scene("oscillator"), "--set", "start_time=1", "--dt", "1e-7", "--steps", "5",
                                   "--repeats", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("1 -> 1.0000005"), std::string::npos) << r.out;
  std::stringstream lines(r.out);
  std::vector<std::string> times;
  for (std::string line; std::getline(lines, line);) {
    std::stringstream cells(line);
    std::vector<std::string> c;
    for (std::string cell; cells >> cell;) c.push_back(cell);
    if (c.size() == 4 && c[3] == "-1") times.push_back(c[0]);  // the rows: a = -x = -1
  }
  EXPECT_EQ(times, (std::vector<std::string>{"1", "1.0000001", "1.0000002", "1.0000003", "1.0000004", "1.0000005"}))
      << r.out;
  const Result late = run_motus(dir, {"run", scene("oscillator"), "--set", "start_time=1234.56789", "--steps", "2",
                                      "--repeats", "1"});
  ASSERT_EQ(late.status, 0) << late.err;
  EXPECT_NE(late.out.find("time         1234.56789 -> "), std::string::npos) << late.out;
}

// Found by running every scene with every integrator: verlet's projected contacts ignore restitution,
// and head_on (e = 1, "the light one bounces back") lost 75 % of its energy, a perfectly inelastic
// contact's loss, with no word but the energy line's. run says why under its passes; symplectic
// Euler's impulses need no such line.
TEST(CliRun, VerletsProjectedContactsSayTheyIgnoreRestitution) {
  TempDir dir;
  const std::string line = "contacts     projected apart (verlet): restitution is not used";
  const Result verlet = run_motus(dir, {"run", scene("head_on"), "--integrator", "verlet", "--repeats", "1"});
  ASSERT_EQ(verlet.status, 0) << verlet.err;
  EXPECT_NE(verlet.out.find(line), std::string::npos) << verlet.out;
  // The loss the line explains: masses 1 and 3 at 1 and -1 m/s, E0 = 2 J; projected apart they move
  // on together at the centre of mass's speed, (1 - 3)/4 = -0.5 m/s: E = 4 · 0.5² / 2 = 0.5 J.
  EXPECT_NE(verlet.out.find("total energy                           2                   0.5"), std::string::npos) << verlet.out;
  const Result impulses = run_motus(dir, {"run", scene("head_on"), "--repeats", "1"});
  ASSERT_EQ(impulses.status, 0) << impulses.err;
  EXPECT_EQ(impulses.out.find("contacts     "), std::string::npos) << impulses.out;
  // A scene of sticks with no balls to bounce has no such line either.
  const Result rope = run_motus(dir, {"run", scene("stick_pendulum"), "--repeats", "1"});
  ASSERT_EQ(rope.status, 0) << rope.err;
  EXPECT_EQ(rope.out.find("contacts     "), std::string::npos) << rope.out;
}

TEST(CliRun, TrajectoryRefusesToOverwriteUnlessAsked) {
  TempDir dir;
  const std::string csv = (dir / "trajectory.csv").string();
  write_file(csv, "precious\n");

  Result r = run_motus(dir, {"run", scene("spring"), "--trajectory", csv});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.rfind("motus: error: " + csv + ": already exists", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("--overwrite"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(csv), "precious\n");

  r = run_motus(dir, {"run", scene("spring"), "--trajectory", csv, "--overwrite"});
  ASSERT_EQ(r.status, 0) << r.err;
  // Header, then one row per step of the course's table (output_interval 0: every step).
  EXPECT_EQ(read_file(csv),
            "t,x0,vx0,kinetic,potential,total\n"
            "0,20,0,0,1000,1000\n"
            "1,20,-10,500,1000,1500\n"
            "2,10,-20,2000,250,2250\n"
            "3,-10,-25,3125,250,3375\n"
            "4,-35,-20,2000,3062.5,5062.5\n"
            "5,-55,-2.5,31.25,7562.5,7593.75\n");

  // A new file is written without --overwrite.
  const std::string fresh = (dir / "fresh.csv").string();
  r = run_motus(dir, {"run", scene("spring"), "--trajectory", fresh});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(fresh));
}

// --overwrite is for an earlier CSV, not for the run's own input: a scene named again as its
// --trajectory (here through "sub/.."), with --overwrite, was replaced by the CSV, exit 0 (an audit).
TEST(CliRun, TrajectoryIsNeverTheScenesOwnFile) {
  TempDir dir;
  fs::create_directories(dir / "sub");
  const std::string scene_file = (dir / "spring.json").string();
  fs::copy_file(scene("spring"), scene_file);
  const std::string before = read_file(scene_file);
  const Result r = run_motus(dir, {"run", scene_file, "--trajectory", (dir / "sub" / ".." / "spring.json").string(), "--overwrite"});
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--trajectory: " + (dir / "sub" / ".." / "spring.json").string() +
                       " is the scene this run reads; write the CSV elsewhere"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(read_file(scene_file), before);
}

TEST(CliList, AScenesFolderThatIsNotThereIsBadInput) {
  // MOTUS_SCENES naming no folder gave an empty list and exit 0; a description over two lines
  // is listed on one.
  TempDir dir;
  Result r = run_motus(dir, {"list"}, {"MOTUS_SCENES=" + (dir / "nowhere").string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("MOTUS_SCENES"), std::string::npos) << r.err;
  fs::create_directories(dir / "scenes");
  write_file(dir / "scenes" / "two_lines.json", R"({"description": "first\nsecond", "dimensions": 1,
      "bodies": [{"mass": 1, "position": [0]}], "dt": 1, "duration": 1})");
  r = run_motus(dir, {"list"}, {"MOTUS_SCENES=" + (dir / "scenes").string()});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("two_lines            first second\n"), std::string::npos) << r.out;
  // A scene named that is not in the folder MOTUS_SCENES names says where it looked.
  r = run_motus(dir, {"run", "spring"}, {"MOTUS_SCENES=" + (dir / "nowhere").string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(r.err, "motus: error: spring: no such file here, nor spring.json in MOTUS_SCENES=" + (dir / "nowhere").string() +
                       " (motus list shows the scenes)\n");
}

TEST(CliRun, TrajectoryRowsComeEveryOutputIntervalHoweverSmall) {
  // The spring's 5 steps of 1 s from t = 1: output_interval 2.5 takes the first steps at or past
  // 1 + 2.5k (t = 4 and the end, 6); an interval far below dt (1e-20 s, which added to t = 1
  // changes nothing) gives a row after every step, as 0 does — and the run ends.
  TempDir dir;
  auto times = [&](const std::string& interval) {
    const std::string name = "interval_" + interval;
    write_file(dir / (name + ".json"),
               R"({"dimensions": 1, "bodies": [{"mass": 10, "position": [20]}], "integrator": "euler",)"
               R"( "forces": [{"type": "spring", "a": 0, "anchor": [0], "stiffness": 5}],)"
               R"( "dt": 1, "duration": 5, "start_time": 1, "output_interval": )" + interval + "}");
    const fs::path csv = dir / (name + ".csv");
    const Result r = run_motus(dir, {"run", (dir / (name + ".json")).string(), "--trajectory", csv.string()});
    EXPECT_EQ(r.status, 0) << interval << ": " << r.err;
    std::string t;
    std::istringstream rows(read_file(csv));
    for (std::string line; std::getline(rows, line);) t += line.substr(0, line.find(',')) + " ";
    return t;
  };
  EXPECT_EQ(times("2.5"), "t 1 4 6 ");
  EXPECT_EQ(times("1e-20"), "t 1 2 3 4 5 6 ");
  EXPECT_EQ(times("1e-320"), "t 1 2 3 4 5 6 ");
  EXPECT_EQ(times("0"), "t 1 2 3 4 5 6 ");
}

}  // namespace

namespace {

// Start-up loads nothing a command does not use (docs/architecture.md): muparser (and its
// libgomp) only for a scene with an equations system, from motus-expressions.so; Box2D and
// Bullet only when a peer runs; OpenGL only to draw. The dynamic loader names every library it
// loads (LD_DEBUG=libs).
TEST(CliStart, ACommandLoadsOnlyTheLibrariesItUses) {
  TempDir dir;
  auto loaded = [](const std::string& log, const std::string& library) {
    std::istringstream lines(log);
    for (std::string line; std::getline(lines, line);)
      if (line.find("calling init: ") != std::string::npos && line.find(library) != std::string::npos) return true;
    return false;
  };
  const char* const heavy[] = {"libmuparser", "libgomp", "libbox2d", "libBullet", "libOSMesa",
                               "motus-expressions.so", "motus-peers.so", "motus-draw.so"};
  const Result help = run_motus(dir, {"--help"}, {"LD_DEBUG=libs"});
  ASSERT_EQ(help.status, 0) << help.err;
  ASSERT_TRUE(loaded(help.err, "libc.so")) << "no loader log:\n" << help.err;
  for (const char* library : heavy) EXPECT_FALSE(loaded(help.err, library)) << "motus --help loaded " << library;
  const Result spring = run_motus(dir, {"run", "spring", "--json"}, {"LD_DEBUG=libs"});
  ASSERT_EQ(spring.status, 0) << spring.err;
  for (const char* library : heavy) EXPECT_FALSE(loaded(spring.err, library)) << "motus run spring loaded " << library;
  // A scene with an equations system loads the module, and muparser with it, and runs.
  const Result lorenz = run_motus(dir, {"run", "lorenz_equations", "--steps", "10", "--json"}, {"LD_DEBUG=libs"});
  ASSERT_EQ(lorenz.status, 0) << lorenz.err;
  EXPECT_TRUE(loaded(lorenz.err, "motus-expressions.so"));
  EXPECT_TRUE(loaded(lorenz.err, "libmuparser"));
  EXPECT_NE(lorenz.out.find("\"steps\": 10"), std::string::npos) << lorenz.out;
}

}  // namespace

// Found by an audit: compare's metrics run noticed Ctrl-C only at a metric sample, steps/200
// apart, so ball_gas with --duration 1e6 (3e5 steps between samples) waited 30 s for the
// backstop ("no safe point came within 30 s") and left its .partial folder. Interrupted after a
// second, it now stops within a fraction of one (the 5 s is a bound on a hang), exit 130, and
// leaves nothing.
TEST(CliCompare, AnInterruptedLongCompareStopsAtOnceAndLeavesNothing) {
  TempDir dir;
  const fs::path out = dir / "x16";
  const pid_t pid = start_motus_with({"compare", "ball_gas", "--duration", "1e6", "--out", out.string()},
                                     {.err = (dir / "err.txt").string(), .folder = dir.path().string()});
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(wait_until_catching(pid, SIGINT)) << read_file(dir / "err.txt");
  ::usleep(1000000);
  const auto asked = std::chrono::steady_clock::now();
  ::kill(pid, SIGINT);
  int raw = 0;
  const bool ended = ended_within(pid, 8, raw);
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
  ASSERT_TRUE(ended) << "still running 8 s after Ctrl-C: " << read_file(dir / "err.txt");
  EXPECT_EQ(WEXITSTATUS(raw), 130) << read_file(dir / "err.txt");
  EXPECT_LT(waited, 5.0) << read_file(dir / "err.txt");
  EXPECT_EQ(read_file(dir / "err.txt").find("no safe point"), std::string::npos) << read_file(dir / "err.txt");
  EXPECT_FALSE(fs::exists(out));
  for (const auto& e : fs::directory_iterator(dir.path()))
    EXPECT_EQ(e.path().filename().string().find("partial"), std::string::npos) << "left behind: " << e.path();
}

// Found by an audit: a misspelt required field read as missing ("mas" gave bodies[0].mass: missing
// (required)), though a misspelt optional one was named with its guess; and a trailing comma after
// a scene's last field was blamed on that field ("duration: malformed JSON"), which was read whole.
TEST(CliErrors, AMisspeltRequiredFieldAndATrailingCommaAreNamedAsWhatTheyAre) {
  TempDir dir;
  const auto line_for = [&](const std::string& name, const std::string& text) {
    const std::string file = (dir / name).string();
    write_file(file, text);
    const Result r = run_motus(dir, {"run", file});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
    const std::string prefix = "motus: error: " + file + ": ";
    EXPECT_EQ(r.err.rfind(prefix, 0), 0u) << r.err;
    return r.err.substr(std::min(prefix.size(), r.err.size()));
  };
  EXPECT_EQ(line_for("mas.json", R"({"dimensions": 1, "bodies": [{"mas": 1, "position": [0]}], "dt": 0.1, "duration": 1})"),
            "bodies[0].mas: unknown field, did you mean mass? (mass is required)\n");
  EXPECT_EQ(line_for("duratoin.json", R"({"dimensions": 1, "bodies": [{"mass": 1, "position": [0]}], "dt": 0.1, "duratoin": 1})"),
            "duratoin: unknown field, did you mean duration? (duration is required)\n");
  EXPECT_EQ(line_for("variabels.json", R"({"system": {"type": "equations", "variabels": ["x"], "equations": {"x": "1"},
      "initial": [1]}, "dt": 0.1, "duration": 1})"),
            "system.variabels: unknown field, did you mean variables? (variables is required)\n");
  // A field far from the missing one is no slip for it: still missing.
  EXPECT_EQ(line_for("no_mass.json", R"({"dimensions": 1, "bodies": [{"position": [0], "weight": 1}], "dt": 0.1, "duration": 1})"),
            "bodies[0].mass: missing (required)\n");
  EXPECT_EQ(line_for("bad_trailing_comma.json",
                     R"({"dimensions": 1, "bodies": [{"mass": 1, "position": [0]}], "dt": 0.1, "duration": 1,})"),
            "malformed JSON at line 1, column 86: syntax error while parsing object key - unexpected '}'; expected string "
            "literal\n");
  EXPECT_EQ(line_for("body_trailing_comma.json",
                     R"({"dimensions": 1, "bodies": [{"mass": 1, "position": [0],}], "dt": 0.1, "duration": 1})"),
            "bodies[0]: malformed JSON at line 1, column 58: syntax error while parsing object key - unexpected '}'; "
            "expected string literal\n");
  // (A missing comma is still at the field it follows: the parser stopped right after its value.)
  EXPECT_EQ(line_for("no_comma.json", R"({"dimensions": 1, "bodies": [{"mass": 1 "position": [0]}], "dt": 0.1, "duration": 1})"),
            "bodies[0].mass: malformed JSON at line 1, column 50: syntax error while parsing object - unexpected string "
            "literal; expected '}'\n");
}

// A scene that starts overlapping (two balls, or a ball outside its box) is moved apart before the
// first step, as documented (docs/scene-format.md, "Overlap"): said in one note on standard error,
// never standard output (--json's object is there), so that a typo in a position does not give a
// plausible run without a word. A scene without overlap — every shipped one — gets no note.
TEST(CliRun, AStartThatOverlapsIsSaidInOneNoteOnStandardError) {
  TempDir dir;
  const std::string two = (dir / "two.json").string();
  write_file(two, R"({"dimensions": 2, "bodies": [{"mass": 1, "radius": 0.5, "position": [0, 0], "velocity": [1, 0]},
      {"mass": 1, "radius": 0.5, "position": [0.9, 0], "velocity": [-1, 0]}], "integrator": "symplectic-euler",
      "dt": 0.01, "duration": 0.1})");
  const Result pair = run_motus(dir, {"run", two, "--json"});
  ASSERT_EQ(pair.status, 0) << pair.err;
  EXPECT_EQ(pair.err, "note: " + two + ": bodies 0 and 1 start overlapping by 0.1 m; motus moves them apart before the "
                      "first step\n");
  EXPECT_TRUE(nlohmann::json::accept(pair.out)) << pair.out;
  const std::string outside = (dir / "outside.json").string();
  write_file(outside, R"({"dimensions": 2, "bodies": [{"mass": 1, "radius": 0.5, "position": [8, 1], "velocity": [0, 0]}],
      "colliders": [{"type": "box", "min": [0, 0], "max": [5, 5]}], "integrator": "symplectic-euler", "dt": 0.01,
      "duration": 0.1})");
  const Result out = run_motus(dir, {"run", outside});
  ASSERT_EQ(out.status, 0) << out.err;
  EXPECT_EQ(out.err, "note: " + outside + ": body 0 starts outside box 0, 3.5 m into its wall; motus moves it into the box "
                     "before the first step\n");
  EXPECT_EQ(out.out.find("note"), std::string::npos) << out.out;
  for (const auto& e : fs::directory_iterator(kScenes)) {
    if (e.path().extension() != ".json") continue;
    const Result r = run_motus(dir, {"run", e.path().string(), "--duration", "0.01"});
    EXPECT_EQ(r.status, 0) << e.path() << ": " << r.err;
    EXPECT_EQ(r.err.find("note:"), std::string::npos) << e.path() << ": " << r.err;
  }
}
