// `motus grade` and students' plug-ins, as an instructor and a student meet them
// (assignments/README.md, docs/grading.md). The numbers come from the assignments themselves:
// each test's points in its rubric.json, the mistakes it names in "catches", the tests an
// untouched starter passes in assignment.json — and the seeded mistakes of
// tests/grading/seeded_bugs.json, each made from the reference solution by one replacement.
//
// Grading needs user namespaces for bubblewrap; where the machine has none, the tests that
// grade in the sandbox say so and skip (this machine has them).
#include <sched.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <cmath>
#include <csignal>
#include <functional>
#include <sstream>
#include <regex>
#include <string>
#include <tuple>

#include "grade_harness.hpp"
#include "motus/grade/grader.hpp"
#include "motus/grade/sandbox.hpp"
#include "motus/grade/wire.hpp"

namespace {

using namespace motus_test;
using nlohmann::json;

std::string fmt_points(double p) {
  std::ostringstream s;
  s << p;
  return s.str();
}

// ---------------------------------------------------------------------------------------------------
// The reference solutions and the starters

TEST(Grade, EveryReferenceSolutionScoresFullMarks) {
  NEEDS_SANDBOX();
  for (const auto& a : kAll) {
    TempDir dir;
    const auto r = run_motus(dir, {"grade", a, (fs::path(kAssignments) / a / "solution").string(), "--hidden", hidden(a),
                                   "--results", (dir / "results.json").string()});
    ASSERT_EQ(r.status, 0) << a << ": " << r.err;
    const json result = read_json(dir / "results.json");
    expect_valid_gradescope(result);
    double max = 0;
    for (const auto& [name, p] : points(a)) max += p;
    EXPECT_EQ(result["max_score"].get<double>(), max) << a;
    EXPECT_EQ(result["score"].get<double>(), max) << a << ": failed " << ::testing::PrintToString(failed(result)) << "\n"
                                                  << r.out;
    EXPECT_EQ(result["tests"].size(), points(a).size() + 2) << a;  // and "files", "build"
  }
}

TEST(Grade, EveryStarterScoresOnlyTheTestsItCannotFail) {
  NEEDS_SANDBOX();
  for (const auto& a : kAll) {
    TempDir dir;
    const auto r = run_motus(dir, {"grade", a, (fs::path(kAssignments) / a / "starter").string(), "--hidden", hidden(a),
                                   "--results", (dir / "results.json").string()});
    ASSERT_EQ(r.status, 0) << a << ": " << r.err;
    const json result = read_json(dir / "results.json");
    expect_valid_gradescope(result);
    const json manifest = read_json(fs::path(kAssignments) / a / "assignment.json");
    std::set<std::string> may_pass = {"files", "build"};
    double expected = 0;
    const auto p = points(a);
    for (const auto& name : manifest["starter_passes"]) {
      may_pass.insert(name.get<std::string>());
      if (p.count(name.get<std::string>())) expected += p.at(name.get<std::string>());
    }
    EXPECT_EQ(result["score"].get<double>(), expected) << a;
    for (const auto& t : result["tests"]) {
      const std::string name = t["name"].get<std::string>().substr(0, t["name"].get<std::string>().find(':'));
      EXPECT_EQ(t["status"] == "passed", may_pass.count(name) > 0) << a << ": " << name << ": " << t["output"];
      if (t["status"] == "failed") {  // a failed test says what was measured and what was expected
        const std::string output = t["output"].get<std::string>();
        EXPECT_TRUE(output.find("Measured:") != std::string::npos || output.find("Your code") != std::string::npos) << output;
      }
    }
    // A right answer that doing nothing gives (no contact, a stick left alone) scored the starter
    // 3 of 30 and 2 of 21 points: it counts only with one of the tests it names passed too.
    for (const auto& [name, definition] : definitions(a)) {
      if (!definition.contains("counts_with_one_of")) continue;
      const json* t = test_named(result, name);
      ASSERT_NE(t, nullptr) << a << ": " << name;
      EXPECT_EQ((*t)["status"], "failed") << a << ": " << name;
      EXPECT_NE((*t)["output"].get<std::string>().find("Right, but code that does nothing gives this answer too"),
                std::string::npos)
          << a << ": " << name << ": " << (*t)["output"];
    }
  }
}

// The handout's first message: what one Euler step of the course's spring gives, and what it should.
TEST(Grade, AStarterFailureTeachesWithTheCourseNumbers) {
  NEEDS_SANDBOX();
  TempDir dir;
  const auto r = run_motus(dir, {"grade", "integrators", (fs::path(kAssignments) / "integrators/starter").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("Expected: at t = 1: x = 20 v = -10"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("moved x with the new velocity"), std::string::npos) << r.out;
}

// Each handout's table lists every public test with its rubric points (the handout stays true).
TEST(Grade, EveryHandoutListsItsPublicTestsWithTheirPoints) {
  for (const auto& a : kAll) {
    const std::string handout = read_file(fs::path(kAssignments) / a / "README.md");
    const json tests = read_json(fs::path(kAssignments) / a / "tests/public.json");
    const auto p = points(a);
    double total = 0;
    for (const auto& t : tests["tests"]) {
      const std::string name = t["name"].get<std::string>();
      const std::string row = "| `" + name + "` | " + fmt_points(p.at(name)) + " |";
      EXPECT_NE(handout.find(row), std::string::npos) << a << ": the handout has no row " << row;
      total += p.at(name);
    }
    EXPECT_NE(handout.find("(you run them; " + fmt_points(total) + " points)"), std::string::npos) << a;
  }
}

// ---------------------------------------------------------------------------------------------------
// Seeded mistakes: each loses exactly the tests that name it, and keeps every other

class SeededBugs : public ::testing::TestWithParam<std::string> {};

TEST_P(SeededBugs, EachLosesExactlyTheTestsThatNameIt) {
  NEEDS_SANDBOX();
  const std::string assignment = GetParam();
  TempDir dir;
  const fs::path batch = dir / "submissions";
  std::map<std::string, std::string> mistakes;  // submission folder → mistake
  std::map<std::string, json> says;             // mistake → {test: words its failure's output contains}
  const json seeded = read_json(MOTUS_SEEDED_BUGS);
  for (const auto& bug : seeded["bugs"]) {
    if (bug["assignment"] != assignment) continue;
    const std::string mistake = bug["mistake"].get<std::string>();
    const fs::path folder = copy_solution(dir, assignment, "submissions/" + mistake);
    const fs::path file = folder / bug["file"].get<std::string>();
    std::string source = read_file(file);
    for (const auto& pair : bug["replace"]) {
      const std::string find = pair[0].get<std::string>(), replace = pair[1].get<std::string>();
      const size_t at = source.find(find);
      ASSERT_NE(at, std::string::npos) << mistake << ": the solution no longer has " << find;
      ASSERT_EQ(source.find(find, at + 1), std::string::npos) << mistake << ": " << find << " is not unique";
      source.replace(at, find.size(), replace);
    }
    write_file(file, source);
    mistakes[mistake] = mistake;
    if (bug.contains("says")) says[mistake] = bug["says"];
  }
  ASSERT_GE(mistakes.size(), 2u) << assignment;
  const auto r = run_motus(dir, {"grade", assignment, "--batch", batch.string(), "--jobs", "2", "--hidden",
                                 hidden(assignment), "--out", (dir / "results").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto defs = definitions(assignment);
  const auto p = points(assignment);
  double max = 0;
  for (const auto& [name, pts] : p) max += pts;
  for (const auto& [folder, mistake] : mistakes) {
    const json result = read_json(dir / "results" / (folder + ".json"));
    expect_valid_gradescope(result);
    std::set<std::string> naming;
    double lost = 0;
    for (const auto& [name, t] : defs)
      if (t.contains("catches") &&
          std::find(t["catches"].begin(), t["catches"].end(), json(mistake)) != t["catches"].end()) {
        naming.insert(name);
        lost += p.at(name);
      }
    EXPECT_FALSE(naming.empty()) << mistake << ": no test names it";
    // And a test whose right answer is what code that does nothing gives (counts_with_one_of) when
    // the mistake fails every test it counts with.
    std::set<std::string> losing = naming;
    for (const auto& [name, t] : defs)
      if (t.contains("counts_with_one_of") && !naming.count(name) &&
          std::all_of(t["counts_with_one_of"].begin(), t["counts_with_one_of"].end(),
                      [&](const json& gate) { return naming.count(gate.get<std::string>()) > 0; })) {
        losing.insert(name);
        lost += p.at(name);
      }
    EXPECT_EQ(failed(result), losing) << assignment << ": " << mistake;
    // Each failure that names the mistake teaches with its hint: the numbers came out wrong, or
    // they stopped the run (an inverted step-size control chose a step of 0: that failure said so
    // and no more). (Not a crash: its hint would be about something else.)
    long checked = 0;
    for (const auto& name : naming) {
      const json* t = test_named(result, name);
      if (t == nullptr || (!defs.at(name).contains("hint") && !defs.at(name).contains("hints"))) continue;
      const std::string output = (*t)["output"].get<std::string>();
      if (output.find("was killed by") != std::string::npos || output.find("ran out of its") != std::string::npos) continue;
      ++checked;
      EXPECT_NE(output.find("This usually means: "), std::string::npos) << mistake << ": " << name << ": " << output;
    }
    // The failure names the student's function and the quantity that is wrong, as measured.
    if (says.count(mistake))
      for (const auto& [name, words] : says.at(mistake).items()) {
        const json* t = test_named(result, name);
        ASSERT_NE(t, nullptr) << mistake << ": " << name;
        EXPECT_NE((*t)["output"].get<std::string>().find(words.get<std::string>()), std::string::npos)
            << mistake << ": " << name << " should say \"" << words.get<std::string>() << "\": " << (*t)["output"];
      }
    // (The step-size controls' mistakes stop the run: their failures must be among those checked.)
    if (mistake.rfind("controller-", 0) == 0) {
      EXPECT_GT(checked, 0) << mistake;
    }
    EXPECT_EQ(result["score"].get<double>(), max - lost) << assignment << ": " << mistake;
    // The message students see at once counts only the tests they see now: a hidden test's
    // failure must not show through its totals (Gradescope hides the total while one is hidden).
    double shown_score = 0, shown_max = 0;
    long shown = 0, shown_passed = 0, not_shown = 0;
    for (const auto& t : result["tests"]) {
      if (t["number"].get<std::string>().rfind("0.", 0) == 0) continue;  // files and build
      if (t["visibility"] != "visible") {
        ++not_shown;
        continue;
      }
      ++shown, shown_passed += t["status"] == "passed";
      shown_score += t["score"].get<double>(), shown_max += t["max_score"].get<double>();
    }
    ASSERT_GT(not_shown, 0) << assignment << ": its hidden tests were given";
    const std::string output = result["output"].get<std::string>();
    EXPECT_NE(output.find(fmt_points(shown_score) + " of " + fmt_points(shown_max) + " points on the " +
                          std::to_string(shown) + " tests shown now; " + std::to_string(shown_passed) + " of them passed. " +
                          std::to_string(not_shown) + " more test"),
              std::string::npos)
        << output;
    EXPECT_EQ(output.find(fmt_points(max)), std::string::npos) << "the total shows through: " << output;
    EXPECT_EQ(output.find("All tests:"), std::string::npos) << output;
  }
  // The scores as a CSV, one row per submission.
  EXPECT_NE(r.out.find("submission,score,max_score,seconds,status"), std::string::npos) << r.out;
  EXPECT_EQ(count_lines(r.out), static_cast<long>(mistakes.size()) + 1) << r.out;
}

INSTANTIATE_TEST_SUITE_P(Assignments, SeededBugs, ::testing::Values("integrators", "collisions", "cloth"));

// ---------------------------------------------------------------------------------------------------
// What a student does with their code in motus (the handouts' commands)

TEST(Plugins, TheSolutionAsAPluginReproducesTheCourseTableInMotusRun) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path plugin = dir / "integrators.so";
  auto r = run_motus(dir, {"grade", "integrators", (fs::path(kAssignments) / "integrators/solution").string(),
                           "--plugin-out", plugin.string()});
  ASSERT_EQ(r.status, 0) << r.err;
  ASSERT_TRUE(fs::exists(plugin));
  r = run_motus(dir, {"run", "spring", "--plugin", plugin.string(), "--integrator", "student:euler", "--trajectory",
                      (dir / "spring.csv").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  // tests/reference/integrators.md, the course's spring: x = 20, 20, 10, −10, −35, −55; v = 0, −10, −20, −25, −20, −2.5.
  const std::string csv = read_file(dir / "spring.csv");
  for (const char* row : {"\n0,20,0,", "\n1,20,-10,", "\n2,10,-20,", "\n3,-10,-25,", "\n4,-35,-20,", "\n5,-55,-2.5,"})
    EXPECT_NE(csv.find(row), std::string::npos) << row << " in\n" << csv;
}

TEST(Plugins, AStudentsCollisionsAreAnEngineColumnInCompare) {
  TempDir dir;
  const auto r = run_motus(dir, {"compare", "newtons_cradle", "--plugin", kAssignmentPlugins + "/collisions-solution.so",
                                 "--json", "--out", (dir / "report").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json summary = json::parse(r.out);
  std::vector<std::string> engines;
  for (const auto& e : summary["engines"]) engines.push_back(e["engine"].get<std::string>());
  EXPECT_EQ(engines, (std::vector<std::string>{"motus", "student", "box2d", "bullet"}));
  for (const auto& e : summary["engines"])
    if (e["engine"] == "student") {
      // The reference solution is motus's formula: the last ball leaves at 1 m/s, the same as motus to rounding.
      EXPECT_LT(e["max_distance_from_motus"].get<double>(), 1e-9);
      EXPECT_EQ(e["momentum"]["final"][0].get<double>(), 1.0);
      EXPECT_EQ(e["notes"], json::array()) << e.dump();  // its code ran
    }
}

// A scene without contacts runs none of a collisions plug-in's code: its column is motus's own
// numbers under the plug-in's name, and a note says so.
// A plug-in's step(x, v) is not symplectic for being one (a student's explicit Euler): what it
// cannot run is said as what it is, a stepper of bodies, not "symplectic".
TEST(Plugins, APluginsStepOfBodiesOnAFirstOrderSystemIsNotCalledSymplectic) {
  TempDir dir;
  const auto r = run_motus(dir, {"bench", "precision", "lorenz", "--plugin", kAssignmentPlugins + "/integrators-solution.so",
                                 "--integrators", "student:euler,verlet", "--levels", "1", "--repeats", "1", "--out",
                                 (dir / "run").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  auto line_of = [&](const std::string& method) {
    std::stringstream lines(r.out);
    for (std::string line; std::getline(lines, line);)
      if (line.rfind(method + " ", 0) == 0) return line;
    return std::string();
  };
  EXPECT_NE(line_of("student:euler").find("cannot run this scene: steps bodies (x and v)"), std::string::npos) << r.out;
  EXPECT_NE(line_of("verlet").find("cannot run this scene: symplectic"), std::string::npos) << r.out;
}

TEST(Plugins, ACompareColumnInWhichNoneOfThePluginsCodeRunsSaysSo) {
  TempDir dir;
  const auto r = run_motus(dir, {"compare", "spring", "--plugin", kAssignmentPlugins + "/collisions-solution.so", "--json",
                                 "--out", (dir / "report").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  bool seen = false;
  const json summary = json::parse(r.out);
  for (const auto& e : summary["engines"])
    if (e["engine"] == "student") {
      seen = true;
      ASSERT_EQ(e["notes"].size(), 1u) << e.dump();
      EXPECT_NE(e["notes"][0].get<std::string>().find("collision rules never run in this scene"), std::string::npos);
      EXPECT_NE(e["notes"][0].get<std::string>().find("motus's own code"), std::string::npos);
    }
  EXPECT_TRUE(seen);
}

// A projection that does not hold the pins (the cloth starter's, which moves nothing) showed only
// "largest stick-length error 0.000e+00": the cloth fell away whole and looked perfect. motus run
// now says how far the pinned bodies got from their pins. With no projection at all, the pinned
// corners fall freely for cloth's 6 s: ½ g T² = 176.58 m, to the rounding of Verlet's
// x_{n+1} = 2 x_n − x_{n−1} + h² a, which grows as n^{3/2} (46,080 substeps: ~4e-7 m). The
// solution's projection places them exactly, and the line is not printed. Found by an audit.
TEST(Plugins, MotusRunSaysHowFarAProjectionLeftThePinnedBodies) {
  TempDir dir;
  auto r = run_motus(dir, {"run", "cloth", "--plugin", kAssignmentPlugins + "/cloth-starter.so", "--repeats", "1", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json starter = json::parse(r.out);
  EXPECT_NEAR(starter["pin_error"]["final"].get<double>(), 0.5 * 9.81 * 6 * 6, 2e-6);
  EXPECT_EQ(starter["pin_error"]["max"], starter["pin_error"]["final"]);  // (it only falls)
  r = run_motus(dir, {"run", "cloth", "--plugin", kAssignmentPlugins + "/cloth-starter.so", "--repeats", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("pins         a pinned body was up to 1.766e+02 m off its pin over the run, 1.766e+02 m at the end"),
            std::string::npos)
      << r.out;
  r = run_motus(dir, {"run", "cloth", "--plugin", kAssignmentPlugins + "/cloth-solution.so", "--repeats", "1", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["pin_error"]["max"], 0);
  r = run_motus(dir, {"run", "cloth", "--repeats", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find("\npins "), std::string::npos) << r.out;
  // A scene may start a body away from its pin: the first projection puts it there, and that start
  // is not the projection's error.
  write_file(dir / "moved_pin.json", R"({"name": "moved_pin", "dimensions": 2,
      "bodies": [{"mass": 1, "position": [0, 0]}, {"mass": 1, "position": [1, 0]}], "sticks": [{"a": 0, "b": 1}],
      "pins": [{"body": 0, "position": [0, 0.5]}], "integrator": "verlet", "dt": 0.01, "duration": 0.1})");
  r = run_motus(dir, {"run", (dir / "moved_pin.json").string(), "--repeats", "1", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["pin_error"]["max"], 0) << r.out;
}

TEST(Plugins, MotusRunSaysWhenTheStudentsPartsResolveTheContacts) {
  // The pass list names the plug-in's collisions and projection (once the same words as motus's own).
  TempDir dir;
  auto r = run_motus(dir, {"run", "bouncing_balls", "--plugin", kAssignmentPlugins + "/collisions-solution.so", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["passes"].back(), "collisions (the plug-in's impulses and times of impact)");
  r = run_motus(dir, {"run", "cloth", "--plugin", kAssignmentPlugins + "/cloth-solution.so", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["passes"].back(), "constraints and contacts (the plug-in's projection)");
  r = run_motus(dir, {"run", "bouncing_balls", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(json::parse(r.out)["passes"].back(), "collisions (impulses at the time of impact)");
}

TEST(Plugins, AStudentsIntegratorRunsInBenchPrecisionAndRender) {
  TempDir dir;
  const std::string plugin = kAssignmentPlugins + "/integrators-solution.so";
  auto r = run_motus(dir, {"bench", "precision", "kepler", "--plugin", plugin, "--integrators", "rk4,student:rk4",
                           "--levels", "2", "--repeats", "1", "--csv", (dir / "p.csv").string(), "--out",
                           (dir / "sweep").string()});  // (its page in the test's folder, not the build's runs/)
  ASSERT_EQ(r.status, 0) << r.err;
  // The same method in both: the same errors, digit for digit in the table's 4 digits.
  const std::string csv = read_file(dir / "p.csv");
  std::vector<std::string> errors[2];
  std::stringstream lines(csv);
  std::string line;
  while (std::getline(lines, line)) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, ',')) cells.push_back(cell);
    if (cells.size() > 7 && (cells[1] == "rk4" || cells[1] == "student:rk4")) errors[cells[1] == "rk4" ? 0 : 1].push_back(cells[7]);
  }
  ASSERT_EQ(errors[0].size(), 2u) << csv;
  for (size_t i = 0; i < 2; ++i) EXPECT_NEAR(std::stod(errors[0][i]), std::stod(errors[1][i]), 1e-12 + 1e-9 * std::stod(errors[0][i]));
  r = run_motus(dir, {"render", "cloth", "--plugin", kAssignmentPlugins + "/cloth-solution.so", "--out",
                      (dir / "frames").string(), "--duration", "0.1", "--size", "160x120", "--fps", "10"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "frames/frame_00001.png"));
}

// ---------------------------------------------------------------------------------------------------
// A plug-in that cannot be used: one line, exit 2

TEST(Plugins, FaultsAreOneLineAndExitTwo) {
  TempDir dir;
  write_file(dir / "notes.so", "these are my notes, not a shared library\n");
  const std::string solution = kAssignmentPlugins + "/integrators-solution.so";
  // A copy cut short: mapped past its end, its first read was SIGBUS (exit 135). Found by an audit.
  write_file(dir / "cut.so", read_file(solution).substr(0, 10000));
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{"run", "spring", "--plugin", (dir / "missing.so").string()}, "no such file"},
      {{"run", "spring", "--plugin", (dir / "notes.so").string()}, "not a plug-in motus can load"},
      {{"run", "spring", "--plugin", kPlugins + "/no_entry.so"}, "no entry point motus_plugin"},
      {{"run", "spring", "--plugin", kPlugins + "/old_version.so"}, "built for plug-in interface 1"},
      {{"run", "spring", "--plugin", solution, "--plugin", solution}, "clashes with"},
      {{"run", "spring", "--plugin", (dir / "cut.so").string(), "--integrator", "student:euler"},
       "cut short (a copy that did not finish?)"},
      // Names a reader cannot tell from a built-in engine's, or that break a line (found by an audit).
      {{"compare", "head_on", "--plugin", kPlugins + "/named_1.so", "--out", (dir / "c").string()},
       "its name \"Box2D\" is a built-in engine's (box2d)"},
      {{"list", "--plugin", kPlugins + "/named_2.so"}, "its name must be 1 to 40 letters, digits"},
      {{"run", "lorenz", "--plugin", kPlugins + "/misbehaving.so", "--integrator", "bad:throws"},
       "bad:throws: threw std::runtime_error: thrown on purpose"},
      {{"run", "spring", "--integrator", "student:euler"}, "load its plug-in with --plugin"},
      // (a column of integrators only, none of them chosen: it would have run motus's own code)
      {{"compare", "oscillator", "--plugin", kPlugins + "/misbehaving.so", "--out", (dir / "c").string()},
       "bad brings integrators only"},
  };
  for (const auto& c : cases) {
    const auto r = run_motus(dir, c.args);
    EXPECT_EQ(r.status, 2) << c.says << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
}

TEST(Plugins, APluginsBrokenNumbersAreItsOwnFailureNeverAPerfectRun) {
  // NaN from a plug-in's integrator: run names the plug-in (not "a smaller --dt" alone); compare's
  // column is not finite, never 0 (std::max(0, NaN) is 0); a controller that keeps a rejected
  // step's size ends the run, exit 1 (it tried the same step for ever).
  TempDir dir;
  const std::string plugin = kPlugins + "/misbehaving.so";
  Result r = run_motus(dir, {"run", "lorenz", "--plugin", plugin, "--integrator", "bad:nan"});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("check the plug-in's integrator bad:nan (" + plugin + ")"), std::string::npos) << r.err;
  r = run_motus(dir, {"compare", "oscillator", "--plugin", plugin, "--integrator", "bad:nan", "--engines", "motus,bad",
                      "--out", (dir / "c").string(), "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);  // (a range-for over parse(...).at(...) reads a dead temporary)
  int bad_columns = 0;  // (the plug-in's column is there: the checks below ran)
  for (const auto& e : report.at("engines"))
    if (e.at("engine") == "bad") {
      ++bad_columns;
      for (const char* field : {"max_energy_error", "max_distance_from_exact"})
        EXPECT_FALSE(e.at(field).is_number() && e.at(field).get<double>() == 0) << field << ": " << e.dump();
    }
  EXPECT_EQ(bad_columns, 1) << report.at("engines").dump();
  // A projection that answers NaN: the run's largest stick and pin errors are not finite (null),
  // not the last finite ones (std::max drops a NaN: an audit read 32.3 and 0 of a NaN rope).
  r = run_motus(dir, {"run", "rope", "--plugin", kPlugins + "/nan_projection.so", "--json"});
  EXPECT_EQ(r.status, 1) << r.err;
  const nlohmann::json rope = nlohmann::json::parse(r.out);
  EXPECT_EQ(rope.at("finite"), false);
  for (const char* error : {"constraint_error", "pin_error"})
    for (const char* which : {"max", "final"}) EXPECT_TRUE(rope.at(error).at(which).is_null()) << error << "." << which << ": " << rope.dump();
  r = run_motus(dir, {"run", "lorenz", "--plugin", plugin, "--integrator", "bad:keeps-h"});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("did not shrink a rejected step"), std::string::npos) << r.err;
  // A controller that shrinks every step, accepted ones too, never reaches the end: motus run went
  // on for ever (the grader stopped it at its step limit). Found by an audit. h halves from
  // lorenz's dt, 0.001, until it is below 1e-14 × max(1, t): t is then 0.002 less a rounding.
  r = run_motus(dir, {"run", "lorenz", "--plugin", plugin, "--integrator", "bad:shrinks-h"});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("step size underflow at t = 0.002:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("a step size that shrinks without end?"), std::string::npos) << r.err;
}

// A plug-in that calls exit(0) ended motus with status 0 and no word, its report folder left
// half-written (found by an audit): a run that did not finish read as one that went well.
TEST(Plugins, AnExitInAPluginsCodeIsAFailedRunNamingIt) {
  TempDir dir;
  const std::string plugin = kPlugins + "/misbehaving.so";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", "spring", "--plugin", plugin, "--integrator", "bad:exits", "--json"},
        std::vector<std::string>{"compare", "spring", "--plugin", plugin, "--integrator", "bad:exits", "--engines",
                                 "motus,bad", "--out", (dir / "c").string()}}) {
    const Result r = run_motus(dir, args);
    EXPECT_EQ(r.status, 1) << args[0] << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("motus: the run did not finish: code in the plug-in " + plugin + " called exit()"),
              std::string::npos)
        << r.err;
  }
  EXPECT_FALSE(fs::exists(dir / "c"));
}

// A plug-in's code runs in motus's process and shares its standard output. Found by an audit: a
// student's debugging line per step went into --json's object (json.load failed at its first
// character) and between the rows of --trajectory -; and it came once per timing run (six times
// over by default, twice with --repeats 1 when the step table is printed), where the handout
// says once. Now the data keep standard output to themselves (the plug-in's lines go to standard
// error), and the timing runs after the reported one print nowhere.
TEST(Plugins, WhatAPluginPrintsComesOnceAndNeverInsideTheData) {
  TempDir dir;
  const std::string plugin = kPlugins + "/misbehaving.so";
  auto lines_with = [](const std::string& text, const std::string& words) {
    long n = 0;
    for (size_t at = text.find(words); at != std::string::npos; at = text.find(words, at + 1)) ++n;
    return n;
  };
  const std::string line = "bad:prints step at t = ";
  // spring: dt = 1, 5 steps; the step table is printed (a first run that writes, then the timed ones).
  Result r = run_motus(dir, {"run", "spring", "--plugin", plugin, "--integrator", "bad:prints"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lines_with(r.out, line), 5) << r.out;
  r = run_motus(dir, {"run", "spring", "--plugin", plugin, "--integrator", "bad:prints", "--repeats", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lines_with(r.out, line), 5) << r.out;
  r = run_motus(dir, {"run", "spring", "--plugin", plugin, "--integrator", "bad:prints", "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::accept(r.out)) << r.out;
  EXPECT_EQ(lines_with(r.err, line), 5) << r.err;
  r = run_motus(dir, {"run", "spring", "--plugin", plugin, "--integrator", "bad:prints", "--trajectory", "-"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(lines_with(r.out, line), 0) << r.out;
  EXPECT_EQ(r.out.rfind("t,x0,vx0,kinetic,potential,total\n0,20,0,", 0), 0u) << r.out;
  EXPECT_EQ(count_lines(r.out), 7) << r.out;  // the header and t = 0 … 5
  r = run_motus(dir, {"compare", "spring", "--plugin", plugin, "--integrator", "bad:prints", "--engines", "motus,bad",
                      "--out", (dir / "c").string(), "--json"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(nlohmann::json::accept(r.out)) << r.out;
  EXPECT_EQ(lines_with(r.err, line), 5) << r.err;  // the metrics run's five steps; no timing round's
}

// Found by an assignments audit: an impulse over the sum of the masses, or a bounce written for the
// floor alone, showed only as "more than 1500 collisions in one step ... (does it find a contact
// between balls that are moving apart?)" or as a NaN time of impact: a wrong impulse read as a
// time of impact's mistake. motus checks Newton's law of restitution after each of the plug-in's
// impulses and bounces, and names the function and the numbers.
TEST(Plugins, AWrongImpulseOrBounceStopsTheRunNamingItsNumbers) {
  TempDir dir;
  const std::string plugin = kPlugins + "/wrong_impulses.so";
  // head_on: masses 1 and 3 meet at u = (v_b - v_a).n = -1 - 1 = -2 m/s, e = 1. Over m_a + m_b
  // the impulse is J = -(1 + 1)(-2)/4 = 1 (not 3): v_a' = 1 - 1/1 = 0, v_b' = -1 + 1/3, so
  // u' = -2/3 — still approaching, where e = 1 asks them to separate at -e u = 2.
  Result r = run_motus(dir, {"run", "head_on", "--plugin", plugin});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("the impulse between balls 0 and 1 left them approaching at -0.666667 m/s along the normal, "
                       "where restitution e = 1 asks them to separate at -e u = 2 m/s (they met at u = -2 m/s)"),
            std::string::npos)
      << r.err;
  // One ball at (2, 0) m/s into the right face of a box (normal (-1, 0)): the floor's rule flips
  // v_y = 0 and leaves n.v = -2, where e = 1 asks +2.
  write_file(dir / "side_wall.json", R"({"name": "side_wall", "dimensions": 2,
    "bodies": [{"mass": 1, "radius": 0.5, "position": [5, 5], "velocity": [2, 0]}],
    "colliders": [{"type": "box", "min": [0, 0], "max": [10, 10]}],
    "integrator": "symplectic-euler", "dt": 0.01, "duration": 4})");
  r = run_motus(dir, {"run", (dir / "side_wall.json").string(), "--plugin", plugin});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("the bounce off a wall left ball 0 with n.v = -2 m/s, where restitution e = 1 asks -e n.v = 2 "
                       "m/s (it met the wall, normal (-1, 0), at n.v = -2 m/s)"),
            std::string::npos)
      << r.err;
}

// Found by a grading audit: a time of impact with no "already touching and approaching: 0" case
// returns, for balls a contact has just left touching, the root of a gap a rounding's size below
// zero — a time just before now, which motus took as "no contact". In the billiards break the
// racked balls then passed into each other (an overlap of 0.26 of their radii, in a hidden scene
// only); every public test passed. motus stops the run at that call, naming the numbers.
TEST(Plugins, ATimeOfImpactBeforeNowForBallsThatTouchStopsTheRun) {
  TempDir dir;
  const std::string plugin = kPlugins + "/touching_times.so";
  Result r = run_motus(dir, {"run", "billiards", "--plugin", plugin});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(plugin + ": returned -"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" as the time of impact of two balls whose surfaces are "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" m apart and approaching, where they already touch"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("that is a contact now, t = 0"), std::string::npos) << r.err;
  // Where no balls touch before they meet (head_on: one contact, from 2 m apart) the same
  // plug-in runs to the end: only a time before now for balls that touch is refused.
  r = run_motus(dir, {"run", "head_on", "--plugin", plugin});
  EXPECT_EQ(r.status, 0) << r.err;
}

// Found by the same audit: a time of impact with a plane with no "moving away: never" case gives
// a ball that has just bounced, touching the wall and leaving it, a contact now; the bounce sends
// it back, and the run stopped at the step's limit of contacts saying "(does it find a contact
// between balls that are moving apart?)" — with one ball in the scene. Now the call is named.
TEST(Plugins, AContactWithAWallForABallMovingAwayStopsTheRun) {
  TempDir dir;
  const std::string plugin = kPlugins + "/away_from_walls.so";
  // bouncing_balls: its first bounce off the floor; every ball leaves it at once.
  const Result r = run_motus(dir, {"run", "bouncing_balls", "--plugin", plugin});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(plugin + ": returned 0 as the time of impact of a ball moving away from a plane (at "),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find(" m/s along its normal): it never reaches it, +infinity"), std::string::npos) << r.err;
}

// Found by a student audit: a time of impact with a plane that leaves the radius out of the gap
// (the time the centre reaches the plane) sank the ball into the floor of `drop`, where the run
// went on removing overlaps, gaining energy, and the grader's bounce test said only "0 tops".
// A time within the step must be one at which the bodies touch; so must two balls' (the later root
// is the time they would part again). motus stops the run at that call, naming the numbers.
TEST(Plugins, ATimeOfImpactWhenTheBodiesDoNotTouchStopsTheRun) {
  TempDir dir;
  const std::string centre = kPlugins + "/centre_to_plane.so", later = kPlugins + "/later_root.so";
  // drop (r = 0.5, dt = 1 ms): the centre's time is past the step in which the ball reaches the floor.
  Result r = run_motus(dir, {"run", "drop", "--plugin", centre});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(centre + ": returned "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" m from a plane and moving into it at "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" m/s: it reaches the plane within the 0.001 s left of the step"), std::string::npos) << r.err;
  // And where in the run: the ball's bottom falls 10 m in √(2 · 10 / 9.81) = 1.4278 s, in the 1428th step of 1 ms.
  EXPECT_NE(r.err.find(" (in step 1428, from t = 1.427)"), std::string::npos) << r.err;
  // A small fast ball (r = 0.01 at 10 m/s, 0.05 m above the floor, dt = 0.01 s): the centre's time,
  // 0.005 s, is within the first step, when the ball would be its radius into the floor.
  write_file(dir / "fast_drop.json", R"({"name": "fast_drop", "dimensions": 2,
    "bodies": [{"mass": 1, "radius": 0.01, "position": [0, 0.05], "velocity": [0, -10]}],
    "colliders": [{"type": "plane", "normal": [0, 1], "offset": 0}],
    "integrator": "symplectic-euler", "dt": 0.01, "duration": 0.1})");
  r = run_motus(dir, {"run", (dir / "fast_drop.json").string(), "--plugin", centre});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find(": returned 0.005 as the time of impact of a ball 0.04 m from a plane: then it would be 0.01 m into "
                       "the plane, not touching it (the gap between them is n.p - offset - r)"),
            std::string::npos)
      << r.err;
  // The later root: oblique's balls meet within a step, and the later root is past it.
  r = run_motus(dir, {"run", "oblique", "--plugin", later});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(later + ": returned "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(" m apart and approaching: they meet within the "), std::string::npos) << r.err;
  // Two small balls head-on at 20 m/s (r = 0.01, dt = 0.02 s): they would pass through each other
  // within one step, so both roots are in it (0.049 and 0.05 s), and the later one is refused as such.
  write_file(dir / "fast_pair.json", R"({"name": "fast_pair", "dimensions": 2,
    "bodies": [{"mass": 1, "radius": 0.01, "position": [-0.5, 0], "velocity": [10, 0]},
               {"mass": 1, "radius": 0.01, "position": [0.5, 0], "velocity": [-10, 0]}],
    "integrator": "symplectic-euler", "dt": 0.02, "duration": 0.1})");
  r = run_motus(dir, {"run", (dir / "fast_pair.json").string(), "--plugin", later});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("then they touch moving apart, having passed through each other (the later root); they meet at the "
                       "earlier one"),
            std::string::npos)
      << r.err;
  // The right times (each plug-in's own for the other kind of body) run the scenes to their end.
  for (const auto& [scene_name, plugin] : std::vector<std::pair<std::string, std::string>>{
           {"drop", later}, {"oblique", centre}, {(dir / "fast_pair.json").string(), centre}}) {
    r = run_motus(dir, {"run", scene_name, "--plugin", plugin});
    EXPECT_EQ(r.status, 0) << scene_name << ": " << r.err;
  }
}

TEST(Plugins, AnExceptionWhileLoadingNamesThePlugin) {
  // Its code runs as soon as it is opened: libstdc++'s two lines ("terminate called ...") and
  // no name before; now one line naming it (and the abort it dies of).
  TempDir dir;
  const auto r = run_motus(dir, {"list", "--plugin", kPlugins + "/throws_on_load.so"});
  EXPECT_EQ(r.status, 128 + SIGABRT) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("the plug-in " + kPlugins + "/throws_on_load.so threw an exception while it was being loaded"),
            std::string::npos)
      << r.err;
}

TEST(Plugins, ACrashNamesThePluginThatWasRunning) {
  TempDir dir;
  const auto r = run_motus(dir, {"run", "lorenz", "--plugin", kPlugins + "/misbehaving.so", "--integrator", "bad:crashes"});
  EXPECT_EQ(r.status, 128 + SIGSEGV) << r.err;  // it cannot be saved: it dies of the signal
  EXPECT_NE(r.err.find("the plug-in " + kPlugins + "/misbehaving.so (bad) crashed the process in its own code (SIGSEGV)"),
            std::string::npos)
      << r.err;
}

// Endless recursion dies of SIGSEGV as a null pointer does, and read as one: the line now says the
// stack overflowed (a null pointer's crash above does not say so).
TEST(Plugins, AStackOverflowIsCalledOne) {
  TempDir dir;
  const auto r = run_motus(dir, {"run", "lorenz", "--plugin", kPlugins + "/misbehaving.so", "--integrator", "bad:recurses"});
  EXPECT_EQ(r.status, 128 + SIGSEGV) << r.err;
  EXPECT_NE(r.err.find("the plug-in " + kPlugins + "/misbehaving.so (bad) crashed the process in its own code (SIGSEGV: the "
                       "stack overflowed, as endless or too deep recursion does)"),
            std::string::npos)
      << r.err;
  const auto null = run_motus(dir, {"run", "lorenz", "--plugin", kPlugins + "/misbehaving.so", "--integrator", "bad:crashes"});
  EXPECT_EQ(null.err.find("stack overflowed"), std::string::npos) << null.err;
}

// ---------------------------------------------------------------------------------------------------
// motus grade itself: bad input, internal failures, no sandbox, the Gradescope zip

TEST(Grade, BadInputIsOneLineAndExitTwo) {
  TempDir dir;
  write_file(dir / "results.json", "{}");
  fs::create_directories(dir / "empty");
  fs::create_directories(dir / "no-tests");
  write_file(dir / "no-tests/none.json", R"({"tests": []})");
  const std::string solution = (fs::path(kAssignments) / "integrators/solution").string();
  // A test's shipped scene misspelt: "tests/public.json: sprnig: cannot be read" named neither the
  // test nor its field (found by an audit).
  json misspelt_scene = definitions("integrators").at("euler.table");
  misspelt_scene["scene"] = "sprnig";
  const std::string misspelt = integrators_with_tests(dir, "misspelt", json::array({misspelt_scene})).string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"grade", "nonsense", solution}, "no such assignment"},
      {{"grade", misspelt, solution}, "public.json: tests[0].scene: \"sprnig\" is no shipped scene, did you mean spring? (motus list shows them"},
      {{"grade", "integrators", (dir / "nowhere").string()}, "no such submission folder"},
      {{"grade", "integrators", solution, "--results", (dir / "results.json").string()}, "--overwrite"},
      {{"grade", "integrators", solution, "--hidden", (dir / "nowhere").string()}, "--hidden: no such folder"},
      {{"grade", "integrators"}, "give a SUBMISSION_DIR"},
      // What --overwrite may replace: a regular file, not a folder or a device (the results are
      // written under another name and renamed over it).
      {{"grade", "integrators", solution, "--results", dir.path().string(), "--overwrite"}, "is a folder"},
      {{"grade", "integrators", solution, "--results", "/dev/null", "--overwrite"}, "not a regular file"},
      {{"grade", "integrators", "--package", "gradescope", "--out", "/dev/null", "--overwrite"}, "not a regular file"},
      {{"grade", "integrators", solution, "--results", ""}, "an empty path"},
      {{"grade", "integrators", solution, "--time-limit", "1e-9"}, "--time-limit: must be from 0.5"},
      {{"grade", "integrators", solution, "--results", "/proc/results.json"}, "cannot be written there"},  // (before grading)
      {{"grade", "integrators", solution, "--hidden", (dir / "empty").string()}, "--hidden: holds no .json test files"},
      {{"grade", "integrators", solution, "--hidden", (dir / "no-tests").string()}, "nor in --hidden"},
      // Options the chosen use would ignore, silently until now.
      {{"grade", "integrators", "--batch", (dir / "empty").string(), "--results", (dir / "r.json").string()},
       "--results: has no use with --batch"},
      {{"grade", "integrators", "--batch", (dir / "empty").string(), "--format", "gradescope"}, "--format: has no use with --batch"},
      {{"grade", "integrators", solution, "--jobs", "2"}, "--jobs: has no use with one SUBMISSION_DIR"},
      {{"grade", "integrators", solution, "--out", (dir / "out").string()}, "--out: has no use with one SUBMISSION_DIR"},
      {{"grade", "integrators", "--package", "gradescope", "--out", (dir / "a.zip").string(), "--plugin-out",
        (dir / "p.so").string()},
       "--plugin-out: has no use with --package"},
      {{"grade", "integrators", solution, "--results", (dir / "same").string(), "--plugin-out", (dir / "same").string()},
       "is --results's file too"},
      // A file called "-" was made (run's --trajectory - is standard output); a batch's folder
      // ending in "." ran every submission, then failed to move the finished folder into place.
      {{"grade", "integrators", solution, "--results", "-"}, "--results -: standard output is the summary's"},
      {{"grade", "integrators", "--batch", (dir / "empty").string(), "--out", (dir / "new/.").string()},
       "--out: ends in \".\": name the new folder (--batch) or zip (--package) itself"},
  };
  for (const auto& [args, says] : cases) {
    const auto r = run_motus(dir, args);
    EXPECT_EQ(r.status, 2) << says << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  }
  EXPECT_EQ(read_file(dir / "results.json"), "{}");  // nothing the user had is overwritten
  for (const char* name : {"r.json", "out", "a.zip", "p.so", "same", "-", "new"}) EXPECT_FALSE(fs::exists(dir / name)) << name;
}

// --package --out autograder (no .zip): zip wrote autograder.zip, and moving "autograder" into place
// failed after the work (exit 1). The zip is written under the name given. (From an audit.)
TEST(Grade, APackageNamedWithoutZipIsWrittenUnderThatName) {
  TempDir dir;
  const auto r = run_motus(dir, {"grade", "integrators", "--package", "gradescope", "--out", (dir / "autograder").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir / "autograder"));
  EXPECT_FALSE(fs::exists(dir / "autograder.zip"));
  const auto listed = run_program(dir, "/usr/bin/unzip", {"-l", (dir / "autograder").string()});
  EXPECT_NE(listed.out.find("run_autograder"), std::string::npos) << listed.out << listed.err;
}

// The grader's own disk full under the compiler (TMPDIR on a 256 kB file system, nearly full): the
// reference solution was graded "does not compile", 0 points, exit 0 — on Gradescope, every
// student. It is the grader's failure: exit 1, and a results file that says so. (From an audit.
// Needs a mount of its own: in a private mount namespace, as root.)
TEST(Grade, AFullDiskUnderTheCompilerIsTheGradersFailureNotTheStudents) {
  NEEDS_SANDBOX();
  TempDir dir;
  fs::create_directories(dir / "small");
  const std::string script =
      "mount -t tmpfs -o size=256k tmpfs \"$1\" && dd if=/dev/zero of=\"$1/fill\" bs=1k count=200 2>/dev/null && "
      "TMPDIR=\"$1\" exec \"$2\" grade integrators \"$3\" --results \"$4\"";
  const auto r = run_program(dir, "/usr/bin/unshare",
                             {"--mount", "--propagation", "private", "/bin/sh", "-c", script, "sh", (dir / "small").string(),
                              kMotus, (fs::path(kAssignments) / "integrators/solution").string(),
                              (dir / "results.json").string()});
  // (unshare itself failing — in a chroot, whose root is no mount point — is no private mount either)
  if ((r.status != 1 && r.err.find("mount") != std::string::npos) || r.err.rfind("unshare: ", 0) == 0)
    GTEST_SKIP() << "no private mounts here: " << r.err;
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("for want of disk space on this machine"), std::string::npos) << r.err;
  const json result = read_json(dir / "results.json");
  expect_valid_gradescope(result);
  EXPECT_NE(result["output"].get<std::string>().find("not the submission's fault"), std::string::npos);
}

// Where grading cannot start (here: a --hidden folder that holds no test file), --results still gets a valid results.json that says why: on Gradescope a missing one
// shows every student only "the autograder failed" (the likely cause there: no user namespaces).
TEST(Grade, WhatStopsTheGradingStillLeavesAResultsFileThatSaysWhy) {
  TempDir dir;
  fs::create_directories(dir / "empty");
  const fs::path submission = copy_solution(dir, "integrators", "solution");
  const auto r = run_motus(dir, {"grade", "integrators", submission.string(), "--hidden", (dir / "empty").string(),
                                 "--results", (dir / "results.json").string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  const json result = read_json(dir / "results.json");
  EXPECT_EQ(result["score"], 0);
  EXPECT_NE(result["output"].get<std::string>().find("--hidden: holds no .json test files"), std::string::npos) << result.dump(2);
}

// --results and --plugin-out spelt two ways (adir/../same.json and same.json) are still one file:
// refused before grading. (Compared as typed, through the existing part only, they graded in full
// and then failed with exit 1, leaving a .partial folder behind.)
TEST(Grade, ResultsAndPluginOutSpeltTwoWaysAreStillOneFile) {
  TempDir dir;
  fs::create_directories(dir / "adir");
  const std::string solution = (fs::path(kAssignments) / "integrators/solution").string();
  const fs::path was = fs::current_path();  // (motus starts where this test is: in `dir`, for the run)
  fs::current_path(dir.path());
  const auto r = run_motus(dir, {"grade", "integrators", solution, "--results", "adir/../same.json", "--plugin-out", "same.json"});
  fs::current_path(was);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("same.json: --plugin-out: is --results's file too"), std::string::npos) << r.err;
  for (const auto& e : fs::directory_iterator(dir.path()))  // no results, no plug-in, no .partial folder
    EXPECT_TRUE(e.path().filename() == "adir" || e.path().extension() == ".txt") << e.path();
}

// The zip's run_autograder grades with the limits it is given: a limit that grading refuses
// (out of range) is refused here, before any zip is written, not by every student's grading on
// Gradescope.
TEST(Grade, ThePackageRefusesTheLimitsThatGradingRefuses) {
  TempDir dir;
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--time-limit", "9999"}, "--time-limit: must be from 0.5 to 600 s"},
      {{"--time-limit", "0.1"}, "--time-limit: must be from 0.5 to 600 s"},
      {{"--memory-limit", "1"}, "--memory-limit: must be from 64 to 65536 MB"},
      {{"--memory-limit", "100000"}, "--memory-limit: must be from 64 to 65536 MB"},
  };
  for (const auto& [limit, says] : cases) {
    std::vector<std::string> args = {"grade", "integrators", "--package", "gradescope", "--out", (dir / "a.zip").string()};
    args.insert(args.end(), limit.begin(), limit.end());
    const auto r = run_motus(dir, args);
    EXPECT_EQ(r.status, 2) << says << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir / "a.zip")) << says;
    fs::remove(dir / "a.zip");
  }
}

// assignment.json and rubric.json are the instructor's, read as strictly as a test file: a field
// misspelt ("pionts" gave a test 0 points; "visibilty" showed an after_due_date test to students
// at once), of the wrong type (a raw JSON library error, exit 1, and no results.json) or missing
// is one line naming the file and the field, exit 2; grading still leaves a results.json that says
// so, and --package writes no zip.
void expect_assignment_refused(const TempDir& dir, const fs::path& assignment, const std::string& file,
                               const std::string& says) {
  const std::string solution = (fs::path(kAssignments) / "integrators/solution").string();
  fs::remove(dir / "r.json");
  auto r = run_motus(dir, {"grade", assignment.string(), solution, "--results", (dir / "r.json").string()});
  EXPECT_EQ(r.status, 2) << says << ": " << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(file + ": " + says), std::string::npos) << r.err;
  ASSERT_TRUE(fs::exists(dir / "r.json")) << says;
  const json result = read_json(dir / "r.json");
  expect_valid_gradescope(result);
  EXPECT_EQ(result["score"], 0);
  EXPECT_NE(result["output"].get<std::string>().find(file + ": " + says), std::string::npos) << result.dump(2);
  r = run_motus(dir, {"grade", assignment.string(), "--package", "gradescope", "--out", (dir / "a.zip").string()});
  EXPECT_EQ(r.status, 2) << says << ": " << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(file + ": " + says), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "a.zip")) << says;
}

// Each case changes a fresh copy of the integrators' assignment.json or rubric.json.
void expect_each_refused(const std::vector<std::tuple<std::string, std::function<void(json&)>, std::string>>& cases) {
  TempDir dir;
  const fs::path assignment = dir / "mine";
  fs::copy(fs::path(kAssignments) / "integrators", assignment, fs::copy_options::recursive);
  for (const auto& [file, change, says] : cases) {
    const std::string original = read_file(assignment / file);
    json document = json::parse(original);
    change(document);
    write_file(assignment / file, document.dump(2));
    expect_assignment_refused(dir, assignment, file, says);
    write_file(assignment / file, original);
  }
}

TEST(Grade, AFieldMisspeltOrMissingInTheRubricOrAssignmentIsNamed) {
  expect_each_refused({
      {"rubric.json", [](json& d) { d["tests"][0]["pionts"] = d["tests"][0]["points"]; d["tests"][0].erase("points"); },
       "tests[0].pionts: unknown field, did you mean points? (expected one of: name, points, visibility)"},
      {"rubric.json", [](json& d) { d["tests"][3]["visibilty"] = "after_due_date"; d["tests"][3].erase("visibility"); },
       "tests[3].visibilty: unknown field"},
      {"rubric.json", [](json& d) { d["tests"][2].erase("points"); }, "tests[2].points: missing (required)"},
      {"rubric.json", [](json& d) { d["tests"][2].erase("visibility"); }, "tests[2].visibility: missing (required)"},
      {"rubric.json", [](json& d) { d["test"] = d["tests"]; }, "test: unknown field, did you mean tests? (expected one of: tests)"},
      {"assignment.json", [](json& d) { d["flgs"] = {"-O3"}; }, "flgs: unknown field"},
  });
}

TEST(Grade, AWrongTypeInTheRubricOrAssignmentIsNamedWithTheTypeExpected) {
  expect_each_refused({
      {"rubric.json", [](json& d) { d["tests"][0]["points"] = "2"; }, "tests[0].points: must be a number, not a string"},
      {"rubric.json", [](json& d) { d["tests"][1]["points"] = nullptr; }, "tests[1].points: must be a number, not null"},
      {"rubric.json", [](json& d) { d["tests"][0]["visibility"] = 1; }, "tests[0].visibility: must be a string, not a number"},
      {"rubric.json", [](json& d) { d["tests"][0] = "euler.table"; }, "tests[0]: must be an object, not a string"},
      {"assignment.json", [](json& d) { d["title"] = 5; }, "title: must be a string, not a number"},
      {"assignment.json", [](json& d) { d["name"] = json::array(); }, "name: must be a string, not an array"},
      {"assignment.json", [](json& d) { d["flags"] = "-O3"; }, "flags: must be an array of strings, not a string"},
      {"assignment.json", [](json& d) { d["files"] = {"integrators.cpp", 3}; }, "files[1]: must be a string, not a number"},
  });
}

// The assignment's own files are read as strictly as a scene: a key twice in one object counted
// once (the last: a rubric entry with "points" twice gave the second without a word), a NUL byte
// ended the file there, and a test file's keys beside "tests" (a misspelt second list) were
// skipped. Each is one line naming the file and the field, exit 2.
TEST(Grade, AnAssignmentsOwnFilesAreReadAsStrictlyAsAScene) {
  TempDir dir;
  const fs::path assignment = dir / "mine";
  fs::copy(fs::path(kAssignments) / "integrators", assignment, fs::copy_options::recursive);
  const std::vector<std::tuple<std::string, std::function<std::string(const std::string&)>, std::string>> cases = {
      {"rubric.json",
       [](const std::string& text) {
         const size_t points = text.find("\"points\"");
         return text.substr(0, points) + "\"points\": 100, " + text.substr(points);
       },
       "tests[0].points: duplicate key \"points\""},
      {"assignment.json", [](const std::string& text) { return std::string(1, '\0') + text; },
       "malformed JSON at line 1, column 1: a NUL byte"},
      {"tests/public.json",
       [](const std::string& text) { return "{\"hidden_tests\": [], " + text.substr(text.find('{') + 1); },
       "hidden_tests: unknown field (expected one of: tests)"},
  };
  for (const auto& [file, change, says] : cases) {
    const std::string original = read_file(assignment / file);
    write_file(assignment / file, change(original));
    expect_assignment_refused(dir, assignment, fs::path(file).filename().string(), says);
    write_file(assignment / file, original);
  }
}

// Each case changes tests/public.json of a fresh copy of its assignment; grading the reference
// solution with it is refused when the tests are read: one line naming the file and the field,
// exit 2 — before any student's code runs.
struct PublicTestsCase {
  std::string assignment;
  std::function<void(json&)> change;
  std::string says;
};

void expect_public_tests_refused(const std::vector<PublicTestsCase>& cases) {
  TempDir dir;
  for (const auto& [name, change, says] : cases) {
    const fs::path assignment = dir / name;
    if (!fs::exists(assignment)) fs::copy(fs::path(kAssignments) / name, assignment, fs::copy_options::recursive);
    const fs::path tests = assignment / "tests/public.json";
    const std::string original = read_file(tests);
    json document = json::parse(original);
    change(document);
    write_file(tests, document.dump(2));
    const auto r = run_motus(dir, {"grade", assignment.string(), (fs::path(kAssignments) / name / "solution").string(),
                                   "--results", (dir / "r.json").string(), "--overwrite"});
    EXPECT_EQ(r.status, 2) << says << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("public.json: " + says), std::string::npos) << r.err;
    write_file(tests, original);
  }
}

// The sticks, pins and walls of a project test, a bounce_ratio's body and a trajectory's rows are
// read when the tests are: a stick naming a body the test does not have went to every student's
// code, which stopped with "a stick names no body" (the student's failed test, for the
// instructor's slip); a string for a body number was a raw JSON library error; a bounce_ratio's
// body past the scene's read past its state; a trajectory's x of the wrong size failed whatever
// the student wrote, and so did a call test's missing argument ("your code stopped the run") or
// misspelt output (read as the student's reply lacking it). Each is one line naming the file and
// the field, exit 2.
TEST(Grade, ATestFilesSticksPinsWallsBodiesAndRowsAreCheckedWhenRead) {
  expect_public_tests_refused({
      {"cloth", [](json& d) { d["tests"][0]["sticks"] = json::parse("[[0, 5, 1]]"); },
       "tests[0].sticks[0][1]: must name one of the test's 2 bodies, a whole number from 0 to 1, not 5"},
      {"cloth", [](json& d) { d["tests"][0]["sticks"] = json::parse("[[\"a\", 1, 1]]"); },
       "tests[0].sticks[0][0]: must name one of the test's 2 bodies, a whole number from 0 to 1, not \"a\""},
      {"cloth", [](json& d) { d["tests"][0]["sticks"] = json::parse("[[0, 1]]"); },
       "tests[0].sticks[0]: must be an array of 3 items, not 2 items"},
      {"cloth", [](json& d) { d["tests"][0]["sticks"] = json::parse("[[1, 1, 1]]"); }, "tests[0].sticks[0]: joins body 1 to itself"},
      {"cloth", [](json& d) { d["tests"][0]["sticks"] = json::parse("[[0, 1, 0]]"); },
       "tests[0].sticks[0][2]: a stick's length must be > 0"},
      {"cloth", [](json& d) { d["tests"][5]["pins"] = json::parse("[[7, [0, 0]]]"); },
       "tests[5].pins[0][0]: must name one of the test's 3 bodies, a whole number from 0 to 2, not 7"},
      {"cloth", [](json& d) { d["tests"][5]["pins"] = json::parse("[[0, [0]]]"); },
       "tests[5].pins[0][1]: must be an array of 2 numbers (the test's dimensions), not [0]"},
      {"cloth", [](json& d) { d["tests"][4]["walls"] = json::parse("[[[0, 0], 0]]"); },
       "tests[4].walls[0][0]: a wall's normal must not be zero"},
      {"cloth", [](json& d) { d["tests"][4]["walls"] = 5; }, "tests[4].walls: must be an array, not a number"},
      {"cloth", [](json& d) { d["tests"][5]["iterations"] = 0; }, "tests[5].iterations: must be from 1 to 1,000,000"},
      {"collisions", [](json& d) { d["tests"][10]["measure"][0]["body"] = 99; },
       "tests[10].measure[0].body: must name one of the scene's"},
      {"collisions", [](json& d) { d["tests"][10]["measure"][0]["bounces"] = 0; },
       "tests[10].measure[0].bounces: must be from 1 to 1,000"},
      {"collisions", [](json& d) { d["tests"][0]["args"].erase("m_b"); },
       "tests[0].args.m_b: missing (collide_balls takes it)"},
      {"collisions", [](json& d) { d["tests"][0]["args"]["mass_b"] = 1; }, "tests[0].args.mass_b: is no argument of collide_balls"},
      {"collisions", [](json& d) { d["tests"][0]["args"]["v_b"] = json::parse("[-1, 0, 0]"); },
       "tests[0].args.v_b: has 3 numbers where the call's other vectors have 2"},
      {"collisions", [](json& d) { d["tests"][4]["args"]["e"] = "0.8"; }, "tests[4].args.e: must be a finite number, not \"0.8\""},
      {"collisions", [](json& d) { d["tests"][0]["expect"]["va"] = d["tests"][0]["expect"]["v_a"]; },
       "tests[0].expect.va: is no output of collide_balls (it gives v_a, v_b)"},
      {"collisions", [](json& d) { d["tests"][5]["expect"]["t"] = json::parse("[1]"); },
       "tests[5].expect.t: must be a number (or \"inf\"), not [1]"},
      {"integrators", [](json& d) { d["tests"][2]["expect"]["x_prev"] = 1; },  // (a "step" test)
       "tests[2].expect.x_prev: is no output of a step (x, v, y, x_start, x_previous, accepted, h)"},
      {"integrators", [](json& d) { d["tests"][0]["expect"][1]["x"] = json::parse("[1, 2]"); },
       "tests[0].expect[1].x: must have 1 number"},
      {"integrators", [](json& d) { d["tests"][0]["expect"][1]["step"] = 1e12; },
       "tests[0].expect[1].step: must be from 0 to 10,000,000"},
  });
}

// A test of the student's integrator that names motus's own ("rk4" for "student:rk4") or none ran
// motus's integrator: every submission passed it, a wrong RK4 too, and grading the reference
// could not show it. One that names an integrator the plug-in does not bring ("student:rk5", or
// "midpoint" in a step test) failed every submission, the reference too ("your code stopped the
// run: unknown integrator"), exit 0. The plug-in's integrators are read from the assignment's
// plugin.cpp. (From an instructor's audit.)
TEST(Grade, ATestOfTheStudentsIntegratorNamesOneThePluginBrings) {
  expect_public_tests_refused({
      {"integrators", [](json& d) { d["tests"][5]["integrator"] = "rk4"; },  // rk4.order
       "tests[5].integrator: \"rk4\" is motus's own integrator; an order test grades the student's code: student:rk4"},
      {"integrators", [](json& d) { d["tests"][5].erase("integrator"); },
       "tests[5].integrator: missing (required): an order test grades the student's integrator, one of student:euler, "
       "student:midpoint, student:rk4,"},
      {"integrators", [](json& d) { d["tests"][0].erase("integrator"); },  // euler.table
       "tests[0].integrator: missing (required): a trajectory test grades the student's integrator"},
      {"integrators", [](json& d) { d["tests"][11].erase("integrator"); },  // symplectic-euler.energy
       "tests[11].integrator: missing (required): an energy test grades the student's integrator"},
      {"integrators", [](json& d) { d["tests"][5]["integrator"] = "student:rk5"; },
       "tests[5].integrator: \"student:rk5\" is none of the student's integrators, did you mean student:rk4?"},
      {"integrators", [](json& d) { d["tests"][16]["integrator"] = "rk4-doubling"; },  // rk4-doubling.kepler
       "tests[16].integrator: \"rk4-doubling\" is motus's own integrator; an adaptive test grades the student's code: "
       "student:rk4-doubling"},
      {"integrators", [](json& d) { d["tests"][2]["integrator"] = "euler"; },  // euler.step-time
       "tests[2].integrator: \"euler\" is motus's own integrator; a step test grades the student's code: student:euler"},
      {"integrators", [](json& d) { d["tests"][2]["integrator"] = "student:euler-x"; },
       "tests[2].integrator: \"student:euler-x\" is none of the student's integrators, did you mean student:euler?"},
      // What the student's integrator is: a fixed-step one in an adaptive test, a step of bodies on
      // a first-order system or given y, an output its kind does not give.
      {"integrators", [](json& d) { d["tests"][16]["integrator"] = "student:rk4"; },
       "tests[16].integrator: student:rk4 takes fixed steps; an adaptive test needs an adaptive integrator of the "
       "student's: student:rk4-doubling"},
      {"integrators", [](json& d) { d["tests"][6]["integrator"] = "student:velocity-verlet"; },  // rk4.stage-time: y' = f(t)
       "tests[6].integrator: student:velocity-verlet steps bodies (x and v), and the test's scene is a first-order system (y)"},
      {"integrators", [](json& d) { d["tests"][17]["integrator"] = "student:euler"; },  // rk4-doubling.step-time: y
       "tests[17].y: student:euler steps bodies: give x and v (one number each), not y"},
      {"integrators", [](json& d) { d["tests"][2]["expect"]["x_start"] = 0; },
       "tests[2].expect.x_start: is no output of a step of student:euler (it gives x and v)"},
      // An assignment whose plug-in brings no integrators: no test may grade one.
      {"collisions", [](json& d) { d["tests"][9]["kind"] = "order"; },
       "tests[9].kind: an order test grades the student's integrator, and the assignment's plug-in (plugin.cpp) brings "
       "none (it brings collision rules)"},
      {"cloth", [](json& d) { d["tests"][6]["integrator"] = "student:verlet"; },
       "tests[6].integrator: \"student:verlet\" is none of the student's integrators: the assignment's plug-in "
       "(plugin.cpp) brings none (it brings a constraint projection)"},
  });
}

// A scene test runs the scene's own integrator, motus's, with the student's collision rules or
// projection in it — unless none of them runs there: motus's verlet projects a collision scene
// with motus's own projection (every submission passed), a scene the integrator cannot run
// stopped every student's run ("rk4 cannot run collisions"), and a scene test in an assignment of
// integrators without one of the student's ran motus alone. A call or project test needs the
// plug-in's collision rules or projection.
TEST(Grade, ASceneTestRunsTheStudentsPartsOrIsRefused) {
  expect_public_tests_refused({
      {"collisions", [](json& d) { d["tests"][9]["integrator"] = "verlet"; },  // newtons-cradle
       "tests[9].integrator: \"verlet\" is motus's and runs none of the student's code here (under verlet, motus's "
       "projection resolves the scene's contacts and sticks; plugin.cpp brings no projection)"},
      {"collisions", [](json& d) { d["tests"][9]["integrator"] = "rk4"; },
       "tests[9].integrator: rk4 cannot run collisions"},
      {"collisions", [](json& d) { d["tests"][9]["integrator"] = "student:rk4"; },
       "tests[9].integrator: \"student:rk4\" is none of the student's integrators: the assignment's plug-in (plugin.cpp) "
       "brings none (it brings collision rules)"},
      {"integrators",
       [](json& d) {
         d["tests"][11]["kind"] = "scene";  // symplectic-euler.energy, as a scene test of bouncing balls
         d["tests"][11]["scene"] = "bouncing_balls";
         d["tests"][11]["measure"] = json::parse(R"([{"kind": "energy", "max": 1}])");
         for (const char* key : {"integrator", "dt", "steps", "expect"}) d["tests"][11].erase(key);
       },
       "tests[11].integrator: missing (required): the scene's own, \"symplectic-euler\", is motus's and runs none of "
       "the student's code here (motus's collision rules resolve the scene's contacts; plugin.cpp brings none)"},
      {"integrators",
       [](json& d) {
         d["tests"][11]["kind"] = "scene";
         d["tests"][11]["scene"] = "bouncing_balls";
         d["tests"][11]["measure"] = json::parse(R"([{"kind": "energy", "max": 1}])");
         for (const char* key : {"dt", "steps", "expect"}) d["tests"][11].erase(key);
       },
       "tests[11].integrator: student:symplectic-euler cannot run the scene's contacts"},
      {"integrators", [](json& d) { d["tests"][11]["scene"] = "bouncing_balls"; },  // an energy test
       "tests[11].integrator: student:symplectic-euler cannot run the scene's contacts"},
      {"integrators",
       [](json& d) {
         d["tests"][11]["kind"] = "scene";  // a scene without contacts: the student's integrator is what runs
         d["tests"][11]["measure"] = json::parse(R"([{"kind": "energy", "max": 1}])");
         for (const char* key : {"integrator", "dt", "steps", "expect"}) d["tests"][11].erase(key);
       },
       "tests[11].integrator: missing (required): the scene's own, \"velocity-verlet\", is motus's and runs none of "
       "the student's code here (the scene has no contacts, sticks or pins); name the student's integrator, one of "
       "student:euler, student:midpoint, …"},
      {"cloth", [](json& d) { d["tests"][0]["kind"] = "call"; },
       "tests[0].kind: a call test calls the student's collision functions, and the assignment's plug-in (plugin.cpp) "
       "brings none (it brings a constraint projection)"},
      {"collisions", [](json& d) { d["tests"][0]["kind"] = "project"; },
       "tests[0].kind: a project test calls the student's constraint projection, and the assignment's plug-in "
       "(plugin.cpp) brings none (it brings collision rules)"},
  });
}

// A final_velocities or final_positions list of another length than the scene's bodies ×
// dimensions, and a max of 0 for a measure that rounding alone makes larger (energy, momentum,
// stick lengths), failed every submission, the reference too ("Expected: (-2, 0, 0)"; 1.58e-16
// against "at most 0"); one halving gave the order check one pair of step sizes, where it reads
// two. Each is refused when the tests are read. (From an instructor's audit.)
TEST(Grade, AScenesExpectedValuesAndBoundsAndAnOrdersHalvingsAreCheckedWhenRead) {
  expect_public_tests_refused({
      {"collisions",  // newtons-cradle: 5 balls in 2-D
       [](json& d) {
         json& expect = d["tests"][9]["measure"][0]["expect"];
         expect.erase(expect.size() - 1);
       },
       "tests[9].measure[0].expect: has 9 numbers; the scene has 5 bodies in 2-D: 10 numbers, body by body"},
      {"collisions", [](json& d) { d["tests"][9]["measure"][0]["kind"] = "final_positions"; d["tests"][9]["measure"][0]["expect"] = {1, 2}; },
       "tests[9].measure[0].expect: has 2 numbers; the scene has 5 bodies in 2-D: 10 numbers"},
      {"collisions", [](json& d) { d["tests"][11]["measure"][1]["max"] = 0; },  // cluster's energy
       "tests[11].measure[1].max: must be > 0 (got 0"},
      {"collisions", [](json& d) { d["tests"][11]["measure"][0]["max"] = -1e-12; },  // its momentum
       "tests[11].measure[0].max: must be > 0"},
      {"cloth", [](json& d) { d["tests"][6]["measure"][0]["max"] = 0; },  // cloth's stick_error
       "tests[6].measure[0].max: must be > 0"},
      {"integrators", [](json& d) { d["tests"][5]["halvings"] = 1; },
       "tests[5].halvings: must be from 2 to 16 (got 1): the order is read at the two finest pairs of successive step "
       "sizes, and 1 halving makes one pair"},
  });
}

// A test file, or the hidden tests' folder, that is not what it should be is named as it is: a
// --hidden folder with no test file in it was only the rubric's "defined in no test file"; a scene
// beside the test files was "tests: must be an array of tests"; a misspelt "tests" was the same; a
// name defined twice in one file named one of its two places. (From an instructor's audit.)
TEST(Grade, ATestFileAndTheHiddenFolderAreNamedForWhatTheyAre) {
  TempDir dir;
  const fs::path assignment = dir / "integrators";
  fs::copy(fs::path(kAssignments) / "integrators", assignment, fs::copy_options::recursive);
  const fs::path hidden = dir / "hidden";
  fs::create_directories(hidden / "scenes");
  const std::string solution = (fs::path(kAssignments) / "integrators/solution").string();
  const std::string tests = read_file(fs::path(kAssignments) / "integrators/hidden/hidden.json");
  auto refused = [&](const std::string& says) {
    const auto r = run_motus(dir, {"grade", assignment.string(), solution, "--hidden", hidden.string()});
    EXPECT_EQ(r.status, 2) << says << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  };
  write_file(hidden / "scenes/spring.json", read_file(scene("spring")));  // (a subfolder is not read)
  refused(hidden.string() + ": --hidden: holds no .json test files (every .json directly in it is read as a file of tests)");
  write_file(hidden / "hidden.json", tests);
  write_file(hidden / "spring.json", read_file(scene("spring")));
  refused("spring.json: tests: missing (required): every .json directly in " + hidden.string() +
          " is read as a file of tests, {\"tests\": [...]} (a test's scene files go in a subfolder, such as scenes/");
  fs::remove(hidden / "spring.json");
  json document = json::parse(tests);
  document["test"] = document["tests"];
  document.erase("tests");
  write_file(hidden / "hidden.json", document.dump(2));
  refused("hidden.json: test: unknown field, did you mean tests? (tests is required)");
  document = json::parse(tests);
  document["tests"].push_back(document["tests"][1]);
  write_file(hidden / "hidden.json", document.dump(2));
  refused("hidden.json: tests[" + std::to_string(document["tests"].size() - 1) + "].name: \"" +
          document["tests"][1]["name"].get<std::string>() + "\" is defined twice (also as tests[1] of this file)");
}

// The plug-in an assignment provides, read from its source: the integrators it brings (by the
// names a test gives them, and their kinds), and its collision rules or projection. One whose
// names are made at run time is not known, and then only motus's own names and a test without an
// integrator are refused.
TEST(Grade, WhatAnAssignmentsPluginBringsIsReadFromItsSource) {
  using motus::grade::read_plugin_parts;
  const auto integrators = read_plugin_parts((fs::path(kAssignments) / "integrators").string(), {"integrators.hpp", "plugin.cpp"});
  ASSERT_TRUE(integrators.known);
  EXPECT_EQ(integrators.file, "plugin.cpp");
  EXPECT_EQ(integrators.prefix, "student");
  std::map<std::string, std::string> kinds;
  for (const auto& i : integrators.integrators) kinds[i.name] = i.kind;
  EXPECT_EQ(kinds, (std::map<std::string, std::string>{{"student:euler", "mechanical"},
                                                       {"student:midpoint", "first_order"},
                                                       {"student:rk4", "first_order"},
                                                       {"student:rk4-doubling", "adaptive"},
                                                       {"student:symplectic-euler", "mechanical"},
                                                       {"student:symplectic-euler-x", "mechanical"},
                                                       {"student:velocity-verlet", "mechanical"},
                                                       {"student:verlet", "position_verlet"}}));
  EXPECT_FALSE(integrators.collisions || integrators.constraints);
  const auto collisions = read_plugin_parts((fs::path(kAssignments) / "collisions").string(), {"collisions.hpp", "plugin.cpp"});
  EXPECT_TRUE(collisions.known && collisions.collisions && !collisions.constraints && collisions.integrators.empty());
  const auto cloth = read_plugin_parts((fs::path(kAssignments) / "cloth").string(), {"cloth.hpp", "plugin.cpp"});
  EXPECT_TRUE(cloth.known && cloth.constraints && !cloth.collisions && cloth.integrators.empty());

  // Names in comments are none; a name made at run time leaves the plug-in unknown.
  TempDir dir;
  const fs::path assignment = dir / "integrators";
  fs::copy(fs::path(kAssignments) / "integrators", assignment, fs::copy_options::recursive);
  std::string plugin = read_file(assignment / "plugin.cpp");
  write_file(assignment / "plugin.cpp", "// plugin.first_order(\"commented\", 1, \"\", f);\n/* plugin.collisions({}); */\n" + plugin);
  auto parts = read_plugin_parts(assignment.string(), {"integrators.hpp", "plugin.cpp"});
  EXPECT_TRUE(parts.known);
  EXPECT_EQ(parts.integrators.size(), 8u);
  EXPECT_FALSE(parts.collisions);
  const std::string rk4 = "plugin.first_order(\"rk4\",";
  ASSERT_NE(plugin.find(rk4), std::string::npos);
  plugin.replace(plugin.find(rk4), rk4.size(), "plugin.first_order(std::string(\"rk\").append(\"4\").c_str(),");
  write_file(assignment / "plugin.cpp", "#include <string>\n" + plugin);
  parts = read_plugin_parts(assignment.string(), {"integrators.hpp", "plugin.cpp"});
  EXPECT_FALSE(parts.known);
  json document = read_json(assignment / "tests/public.json");
  document["tests"][5]["integrator"] = "rk4";
  write_file(assignment / "tests/public.json", document.dump(2));
  const auto r = run_motus(dir, {"grade", assignment.string(), (fs::path(kAssignments) / "integrators/solution").string()});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("public.json: tests[5].integrator: \"rk4\" is motus's own integrator; an order test grades the "
                       "student's code: the plug-in's own, PLUGIN:NAME"),
            std::string::npos)
      << r.err;
}

// Hidden tests kept inside the assignment's folder under a name of their own went into the
// Gradescope zip twice: as hidden/, which run_autograder makes root's only, and again inside the
// assignment's copy, readable by all. They go in once, as hidden/. (From an instructor's audit.)
TEST(Grade, APackageTakesHiddenTestsInsideTheAssignmentOnce) {
  TempDir dir;
  const fs::path assignment = dir / "integrators";
  fs::copy(fs::path(kAssignments) / "integrators", assignment, fs::copy_options::recursive);
  fs::copy(fs::path(kAssignments) / "integrators/hidden", assignment / "tests-2025-hidden", fs::copy_options::recursive);
  fs::create_directory_symlink("tests-2025-hidden", assignment / "hidden-link");
  const auto r = run_motus(dir, {"grade", assignment.string(), "--package", "gradescope", "--out", (dir / "a.zip").string(),
                                 "--hidden", (assignment / "tests-2025-hidden").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto listed = run_program(dir, "/usr/bin/unzip", {"-l", (dir / "a.zip").string()});
  ASSERT_EQ(listed.status, 0) << listed.err;
  long copies = 0;
  std::istringstream lines(listed.out);
  for (std::string line; std::getline(lines, line);) {
    copies += line.find("hidden.json") != std::string::npos;
    EXPECT_EQ(line.find("assignment/tests-2025-hidden"), std::string::npos) << line;
    EXPECT_EQ(line.find("assignment/hidden-link"), std::string::npos) << line;
  }
  EXPECT_EQ(copies, 1) << listed.out;
  EXPECT_NE(listed.out.find(" hidden/hidden.json"), std::string::npos) << listed.out;
  EXPECT_NE(listed.out.find(" assignment/tests/public.json"), std::string::npos) << listed.out;
}

// The rubric's tests not given (no --hidden) are counted by their visibility: a visible test in
// the hidden folder was counted "never shown", an after_published one "shown after the due date".
TEST(Grade, TheTestsNotGivenAreCountedByTheirVisibility) {
  TempDir dir;
  const fs::path assignment = integrators_with_tests(dir, "some", json::array({definitions("integrators").at("euler.table")}));
  json rubric = read_json(assignment / "rubric.json");
  const std::pair<const char*, const char*> left_out[] = {
      {"a", "after_due_date"}, {"b", "after_published"}, {"c", "hidden"}, {"d", "hidden"}, {"e", "visible"}};
  for (const auto& [name, visibility] : left_out) rubric["tests"].push_back({{"name", name}, {"points", 1}, {"visibility", visibility}});
  write_file(assignment / "rubric.json", rubric.dump(2));
  motus::grade::SceneSource scenes;
  scenes.shipped = [](const std::string& name) { return scene(name); };
  const auto a = motus::grade::load_assignment(assignment.string(), std::nullopt, scenes);
  EXPECT_EQ(a.hidden_not_given, 5);
  EXPECT_EQ(a.not_given_when(), "1 shown at once, 1 shown after the due date, 1 shown once the grades are published, 2 never shown");
}

// As root, motus's own files out of the sandbox's user's reach — root's clone in /root, 0700 as
// Debian makes it — are copied into the grading's own folder: every grading failed with "/root
// (mode 0700): the sandbox's user (uid 61000) cannot pass through it", and so did these tests on a
// fresh Debian 12 with the clone in /root (found by running the README's test command there).
// Here motus and its modules are in a 0700 folder; without the sandbox, so that it runs where
// bubblewrap cannot (the sandbox's user is the same).
TEST(Grade, MotusInAFolderOnlyRootCanEnterStillGrades) {
  if (::geteuid() != 0) GTEST_SKIP() << "as root only: only root's gradings run as a sandbox user of their own";
  TempDir dir;
  const fs::path bin = dir / "private/bin";
  fs::create_directories(bin);
  ASSERT_EQ(::chmod((dir / "private").c_str(), 0700), 0);
  for (const auto& e : fs::directory_iterator(fs::path(kMotus).parent_path()))
    if (e.path() == fs::path(kMotus) || (e.path().filename().string().starts_with("motus-") && e.path().extension() == ".so"))
      fs::copy(e.path(), bin / e.path().filename());
  const std::string solution = (fs::path(kAssignments) / "integrators/solution").string();
  const auto r = run_program(dir, (bin / "motus").string(), {"grade", "integrators", solution, "--no-sandbox", "--results",
                                                              (dir / "r.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "r.json");
  EXPECT_EQ(result["score"], 25) << result.dump(2);  // (the solution's full marks on the public tests)
}

// Only the handed-in files themselves are taken: a link (to the solution, say) is not followed,
// and a file over 1 MB is no source code; each says why. (Read through one descriptor that
// follows no link: a link swapped in after a look would otherwise be followed.)
TEST(Grade, AHandedInLinkOrAHugeFileIsNotTaken) {
  TempDir dir;
  const std::string solution = (fs::path(kAssignments) / "integrators/solution/integrators.cpp").string();
  fs::create_directories(dir / "linked");
  fs::create_symlink(solution, dir / "linked/integrators.cpp");
  fs::create_directories(dir / "huge");
  write_file(dir / "huge/integrators.cpp", std::string((1 << 20) + 1, ' '));
  for (const auto& [folder, why] : {std::pair<std::string, std::string>{"linked", "not a regular file (a folder or a link is not taken)"},
                                    {"huge", "larger than 1 MB"}}) {
    const auto r = run_motus(dir, {"grade", "integrators", (dir / folder).string(), "--no-sandbox", "--results",
                                   (dir / (folder + ".json")).string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const json result = read_json(dir / (folder + ".json"));  // (kept: test_named points into it)
    const json* files = test_named(result, "files");
    ASSERT_NE(files, nullptr);
    EXPECT_EQ((*files)["status"], "failed");
    EXPECT_NE((*files)["output"].get<std::string>().find("integrators.cpp: " + why), std::string::npos) << (*files)["output"];
    EXPECT_EQ(result["score"].get<double>(), 0);
    // What the student reads first says the file may be there (it said "is missing", of a file in plain sight).
    EXPECT_NE(result["output"].get<std::string>().find("A handed-in file is missing or cannot be taken: see \"files\"."),
              std::string::npos)
        << result["output"];
  }
}

// A sandbox that cannot reach a folder is the grader's fault: with TMPDIR a 0700 folder of root's,
// the sandbox's user could not enter the work folder, and every student scored 0 with "does not
// compile" (bubblewrap's "Permission denied" shown as the compiler's words). Now the grading stops
// as a grader failure (exit 1; results.json says so) naming the folder. (Root only: without root
// the sandbox runs as the grader's own user, who can enter it.)
TEST(Grade, AFolderTheSandboxCannotEnterIsTheGradersFaultNamed) {
  NEEDS_SANDBOX();
  if (::geteuid() != 0) GTEST_SKIP() << "needs root: the sandbox's user is then another";
  TempDir dir;
  const fs::path closed = dir / "closed";
  fs::create_directories(closed);
  fs::permissions(closed, fs::perms::owner_all);  // 0700
  const fs::path submission = copy_solution(dir, "integrators", "solution");
  const auto r = run_motus(dir, {"grade", "integrators", submission.string(), "--results", (dir / "results.json").string()},
                           {"TMPDIR=" + closed.string()});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find(closed.string() + " (mode 0700): the sandbox's user"), std::string::npos) << r.err;
  const json result = read_json(dir / "results.json");
  EXPECT_EQ(result["extra_data"]["internal_error"], true) << result.dump(2);
  EXPECT_NE(result["output"].get<std::string>().find("fault of the grader"), std::string::npos) << result.dump(2);
  // The same without the sandbox (the code still runs as the sandbox's user), and through a link
  // out of the closed folder (the way as given is what is followed).
  fs::create_directories(dir / "open");
  fs::create_directory_symlink("../open", closed / "link");
  for (const auto& [tmpdir, extra] : {std::pair<fs::path, std::string>{closed, "--no-sandbox"}, {closed / "link", ""}}) {
    std::vector<std::string> args = {"grade", "integrators", submission.string(), "--results", (dir / "again.json").string(),
                                     "--overwrite"};
    if (!extra.empty()) args.push_back(extra);
    const auto again = run_motus(dir, args, {"TMPDIR=" + tmpdir.string()});
    EXPECT_EQ(again.status, 1) << tmpdir << " " << extra << ": " << again.err;
    EXPECT_NE(again.err.find(closed.string() + " (mode 0700): the sandbox's user"), std::string::npos) << again.err;
  }
}

// What a student's code writes reaches the instructor's terminal without its control characters:
// an escape sequence could clear the screen or rewrite the lines above it (the JSON escapes them).
TEST(Grade, AStudentsEscapeSequencesNeverReachTheTerminal) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path submission = solution_with_euler_step_starting(
      dir, "escapes", "throw std::runtime_error(\"\\x1b[2J\\x1b[Hall clear\");", "#include <stdexcept>\n");
  const auto r = run_motus(dir, {"grade", "integrators", submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("?[2J?[Hall clear"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos);
  EXPECT_NE(read_file(dir / "results.json").find("\\u001b[2J"), std::string::npos);  // (the JSON keeps it, escaped)
}

// The integrators solution with the seeded mistakes `mistakes` (tests/grading/seeded_bugs.json)
// and, first in each function of `first_lines`, its line.
std::string solution_with(const std::vector<std::string>& mistakes, const std::map<std::string, std::string>& first_lines) {
  std::string source = read_file(fs::path(kAssignments) / "integrators/solution/integrators.cpp");
  const json seeded = read_json(MOTUS_SEEDED_BUGS);
  for (const std::string& mistake : mistakes) {
    bool found = false;
    for (const auto& bug : seeded["bugs"])
      if (bug["assignment"] == "integrators" && bug["mistake"] == mistake) {
        found = true;
        for (const auto& pair : bug["replace"]) {
          const size_t at = source.find(pair[0].get<std::string>());
          EXPECT_NE(at, std::string::npos) << mistake;
          if (at != std::string::npos) source.replace(at, pair[0].get<std::string>().size(), pair[1].get<std::string>());
        }
      }
    EXPECT_TRUE(found) << "no seeded mistake " << mistake;
  }
  for (const auto& [function, line] : first_lines) {
    const size_t at = source.find("void " + function + "(");
    const size_t body = at == std::string::npos ? at : source.find("{\n", at);
    EXPECT_NE(body, std::string::npos) << "the integrators solution has no " << function;
    if (body != std::string::npos) source.insert(body + 2, "  " + line + "\n");
  }
  return source;
}

// What a test's output shows below the line in which `heading` is last said (to the output's end), or "".
std::string below(const std::string& output, const std::string& heading) {
  const size_t at = output.rfind(heading);
  const size_t end = at == std::string::npos ? at : output.find('\n', at);
  return end == std::string::npos ? "" : output.substr(end + 1);
}

// A student debugging a wrong answer sees their own prints: a test that fails without a crash shows
// what the student's code printed while it ran (std::cout, unflushed till the server ends, and
// std::cerr) — that test's alone, each test having a server of its own — under the test's own
// visibility; a test that passes shows none. The wrong answers are the seeded mistakes the two tests
// catch; an escape sequence in a print reaches the terminal as '?', as a crash's output does.
TEST(Grade, AFailedTestShowsWhatTheStudentsCodePrintedDuringIt) {
  NEEDS_SANDBOX();
  TempDir dir;
  const auto defs = definitions("integrators");
  const fs::path assignment =
      integrators_with_tests(dir, "prints", json::array({defs.at("euler.table"), defs.at("rk4.order"), defs.at("velocity-verlet.order")}));
  json rubric = read_json(assignment / "rubric.json");
  ASSERT_EQ(rubric["tests"][1]["name"], "rk4.order");
  rubric["tests"][1]["visibility"] = "after_due_date";  // (shown with its prints after the due date, not before)
  write_file(assignment / "rubric.json", rubric.dump(2));
  ASSERT_EQ(defs.at("euler.table")["catches"], json::array({"euler-new-velocity"}));
  ASSERT_EQ(defs.at("rk4.order")["catches"], json::array({"rk4-equal-weights"}));
  const std::string euler_says = "euler_step says \x1b[2Jhello", rk4_says = "rk4_step says hello",
                    verlet_says = "velocity_verlet_step says hello";
  const fs::path submission = dir / "debugging";
  fs::create_directories(submission);
  write_file(submission / "integrators.cpp",
             "#include <iostream>\n" + solution_with({"euler-new-velocity", "rk4-equal-weights"},
                                                     {{"euler_step", R"(std::cout << "euler_step says \x1b[2Jhello\n";)"},
                                                      {"rk4_step", R"(std::cerr << "rk4_step says hello" << std::endl;)"},
                                                      {"velocity_verlet_step", R"(std::cout << "velocity_verlet_step says hello\n";)"}}));
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  expect_valid_gradescope(result);
  EXPECT_EQ(failed(result), (std::set<std::string>{"euler.table", "rk4.order"})) << result.dump(2);
  const json* euler = test_named(result, "euler.table");
  const json* rk4 = test_named(result, "rk4.order");
  const json* verlet = test_named(result, "velocity-verlet.order");
  ASSERT_TRUE(euler && rk4 && verlet);
  const std::string euler_output = (*euler)["output"].get<std::string>(), rk4_output = (*rk4)["output"].get<std::string>();
  EXPECT_NE(euler_output.find("\n" + euler_says + "\n"), std::string::npos) << euler_output;
  EXPECT_NE(rk4_output.find("\n" + rk4_says + "\n"), std::string::npos) << rk4_output;
  for (const std::string& other : {rk4_says, verlet_says}) EXPECT_EQ(euler_output.find(other), std::string::npos) << euler_output;
  for (const std::string& other : {euler_says, verlet_says}) EXPECT_EQ(rk4_output.find(other), std::string::npos) << rk4_output;
  EXPECT_EQ((*rk4)["visibility"], "after_due_date");
  EXPECT_EQ((*verlet)["output"].get<std::string>().find("says hello"), std::string::npos) << (*verlet)["output"];
  EXPECT_EQ(result["output"].get<std::string>().find("says hello"), std::string::npos) << result["output"];
  // The summary on the terminal: the prints of the failed tests, control characters as '?'.
  EXPECT_NE(r.out.find("euler_step says ?[2Jhello"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(rk4_says), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos);
}

// A student who prints a megabyte gets, in a failed test's output, what a crash's output shows of
// it, whatever the kind of failure: the end of what it printed — the prints just before it went
// wrong, not the end of the first KBs (the sandbox keeps a flood's first and last 32 KB, the middle
// read and dropped) — cut to the same length and marked as cut. Here one submission fails
// euler.table with wrong numbers and aborts in euler.order (h < 0.5 there), after the same flood.
TEST(Grade, AFloodOfPrintsInAFailedTestIsCutAsACrashsOutputIs) {
  NEEDS_SANDBOX();
  TempDir dir;
  const auto defs = definitions("integrators");
  ASSERT_GE(defs.at("euler.table")["expect"][0]["step"].get<int>(), 1);
  ASSERT_LT(defs.at("euler.order")["dt"].get<double>(), 0.5);
  const fs::path assignment = integrators_with_tests(dir, "flood", json::array({defs.at("euler.table"), defs.at("euler.order")}));
  std::string printed;  // what each test's server prints at its first call: numbered lines, 1 MB and more
  for (int line = 0; printed.size() < (1u << 20); ++line) printed += "flood line " + std::to_string(line) + "\n";
  // and last a line of 1,000 em dashes (3 bytes each) and "!": the last 1,200 bytes start inside a dash.
  std::string dashes;
  for (int k = 0; k < 1000; ++k) dashes += "—";
  printed += dashes + "!\n";
  const fs::path submission = dir / "flooding";
  fs::create_directories(submission);
  write_file(submission / "integrators.cpp",
             "#include <cstdlib>\n#include <iostream>\n#include <string>\n" +
                 solution_with({"euler-new-velocity"},
                               {{"euler_step", "static bool flooded = false; if (!flooded) { flooded = true; for (int line = 0, size = 0; "
                                               "size < (1 << 20); ++line) { const std::string text = \"flood line \" + "
                                               "std::to_string(line) + \"\\n\"; std::cout << text; size += int(text.size()); } "
                                               "for (int k = 0; k < 1000; ++k) std::cout << \"—\"; std::cout << \"!\\n\"; } "
                                               "if (h < 0.5) std::abort();"}}));
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  expect_valid_gradescope(result);
  const json* table = test_named(result, "euler.table");
  const json* order = test_named(result, "euler.order");
  ASSERT_TRUE(table && order);
  EXPECT_EQ((*table)["status"], "failed");
  EXPECT_EQ((*order)["status"], "failed");
  const std::string wrong = (*table)["output"].get<std::string>(), crash = (*order)["output"].get<std::string>();
  EXPECT_NE(crash.find("killed by SIGABRT"), std::string::npos) << crash;
  EXPECT_NE(wrong.find("The end of what your code printed during this test:\n"), std::string::npos) << wrong;
  EXPECT_NE(crash.find("The end of its output:\n"), std::string::npos) << crash;
  const std::string heading = "The end of ";
  const std::string crash_shows = below(crash, heading), wrong_shows = below(wrong, heading);
  // The end of all it printed, cut at its start.
  const std::string cut = "…";
  ASSERT_TRUE(wrong_shows.starts_with(cut)) << wrong_shows;
  const std::string shown = wrong_shows.substr(cut.size());
  EXPECT_GT(shown.size(), 1000u);
  EXPECT_TRUE(printed.substr(0, printed.size() - 1).ends_with(shown)) << shown;  // (its last newline trimmed)
  // From a whole character: the 1,200 bytes' first one falls inside a dash, which is not shown in part.
  EXPECT_TRUE(shown.starts_with("—")) << shown;
  EXPECT_EQ(shown.size(), 1200u - 2) << shown;
  // The crash's the same way, to about the same length: the end of the flood, all of it (the
  // student's prints are not held in a buffer that a crash throws away), and after it the server's
  // own last words on the signal.
  ASSERT_TRUE(crash_shows.starts_with(cut)) << crash;
  EXPECT_LE(crash_shows.size(), cut.size() + 1200) << crash;
  EXPECT_GE(crash_shows.size(), cut.size() + 1200 - 3) << crash;  // (at most a character's continuation bytes less)
  EXPECT_NE(static_cast<unsigned char>(crash_shows[cut.size()]) & 0xC0, 0x80) << crash;
  const size_t flood_end = crash_shows.find("—!\n");
  ASSERT_NE(flood_end, std::string::npos) << crash;
  EXPECT_NE(crash_shows.find("SIGABRT", flood_end), std::string::npos) << crash;
  // Bounded as it was read: the whole results.json is smaller than the 64 KB the sandbox keeps of
  // one test's prints (Limits::output_bytes), which is far less than the megabyte printed.
  EXPECT_LT(fs::file_size(dir / "results.json"), 64u * 1024);
}

// Found by a student audit: a printf just before a crash was not shown, though the handout says a
// failed test shows what the code printed. Standard output to a pipe is held in a buffer, and
// SIGABRT threw it away with the process (std::cerr, unbuffered, was shown).
TEST(Grade, APrintfJustBeforeACrashIsShown) {
  NEEDS_SANDBOX();
  TempDir dir;
  const auto defs = definitions("integrators");
  ASSERT_LT(defs.at("euler.order")["dt"].get<double>(), 0.5);
  const fs::path assignment = integrators_with_tests(dir, "printf", json::array({defs.at("euler.order")}));
  const fs::path submission = dir / "printing";
  fs::create_directories(submission);
  write_file(submission / "integrators.cpp",
             "#include <cstdio>\n#include <cstdlib>\n" +
                 solution_with({}, {{"euler_step", R"(std::printf("euler_step at h = %g\n", h); if (h < 0.5) std::abort();)"}}));
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  const json* order = test_named(result, "euler.order");
  ASSERT_TRUE(order);
  EXPECT_EQ((*order)["status"], "failed");
  const std::string crash = (*order)["output"].get<std::string>();
  const size_t printed = crash.find("euler_step at h = ");
  ASSERT_NE(printed, std::string::npos) << crash;
  EXPECT_NE(crash.find("SIGABRT", printed), std::string::npos) << crash;
}

// Found by a student audit: step doubling without the extrapolation ends Kepler within the test's
// 1e-5 but not within twice motus's own error, and the failure said "larger than allowed",
// beside an Expected line whose 1e-5 the error met. It names the bound it missed.
TEST(Grade, AnAdaptiveTestNamesTheBoundItsErrorMissed) {
  NEEDS_SANDBOX();
  TempDir dir;
  const auto defs = definitions("integrators");
  const json kepler = defs.at("rk4-doubling.kepler");
  ASSERT_EQ(kepler["compare_with"], "rk4-doubling");
  ASSERT_EQ(kepler["factor"], 2);
  const double max_error = kepler["max_error"].get<double>();
  const fs::path assignment = integrators_with_tests(dir, "adaptive", json::array({kepler}));
  const fs::path submission = dir / "no-extrapolation";
  fs::create_directories(submission);
  write_file(submission / "integrators.cpp", solution_with({"doubling-no-extrapolation"}, {}));
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  const json* test = test_named(result, "rk4-doubling.kepler");
  ASSERT_TRUE(test);
  EXPECT_EQ((*test)["status"], "failed");
  const std::string output = (*test)["output"].get<std::string>();
  // Its error (measured: "error E at t = 5") is within the test's own bound, so it missed motus's.
  const std::smatch error = [&] {
    std::smatch m;
    std::regex_search(output, m, std::regex("error ([0-9.e+-]+) at t = 5"));
    return m;
  }();
  ASSERT_FALSE(error.empty()) << output;
  EXPECT_LE(std::stod(error[1].str()), max_error) << output;
  EXPECT_NE(output.find("The error at the end is larger than 2 × motus's rk4-doubling ("), std::string::npos) << output;
  EXPECT_EQ(output.find("larger than allowed"), std::string::npos) << output;
}

// A step-size control turned upside down shrinks the step without end: the run records states
// until memory runs out. It used to end as "killed by SIGABRT" (a JSON array that big cannot be
// destroyed without memory); now the run stops at the most it may record, and the test's hint
// follows, as for wrong numbers.
TEST(Grade, AStepSizeThatShrinksWithoutEndIsTheStudentsErrorWithItsHint) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path submission =
      integrators_solution_with(dir, "inverted", "std::pow(error_ratio, -1.0 / 5)", "std::pow(error_ratio, 1.0 / 5)");
  ASSERT_FALSE(submission.empty());
  const auto r = run_motus(dir, {"grade", "integrators", submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");  // (kept: test_named points into it)
  const json* t = test_named(result, "rk4-doubling.kepler");
  ASSERT_NE(t, nullptr);
  const std::string output = (*t)["output"].get<std::string>();
  EXPECT_EQ(output.rfind("Your code stopped the run: ", 0), 0u) << output;
  EXPECT_NE(output.find("a step size that shrinks without end?"), std::string::npos) << output;
  EXPECT_NE(output.find("This usually means: " + definitions("integrators").at("rk4-doubling.kepler")["hint"].get<std::string>()),
            std::string::npos)
      << output;
}

// Found by a grading audit: a time of impact that loops for ever "timed out ... during
// balls_impact", a name the student never wrote (the plug-in's wire), and a cloth whose sweeps run
// until every stick is exact timed out with no word of constraints.iterations. The student's own
// function is named, and the cloth assignment's timeout_hint follows.
TEST(Grade, ATimeoutNamesTheStudentsFunctionAndTheAssignmentsHint) {
  NEEDS_SANDBOX();
  TempDir dir;
  auto with = [&](const std::string& assignment, const std::string& file, const std::string& find,
                  const std::string& replacement) {
    const fs::path submission = copy_solution(dir, assignment, assignment + "-loops");
    std::string source = read_file(submission / file);
    const size_t at = source.find(find);
    EXPECT_NE(at, std::string::npos) << find;
    if (at != std::string::npos) source.replace(at, find.size(), replacement);
    write_file(submission / file, source);
    return submission;
  };
  const fs::path collisions = with("collisions", "collisions.cpp", "const double R = r_a + r_b;",
                                   "const double R = r_a + r_b;\n  for (volatile int spin = 0;; spin = spin + 1) {}");
  auto r = run_motus(dir, {"grade", "collisions", collisions.string(), "--time-limit", "1", "--results",
                           (dir / "collisions.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json balls = read_json(dir / "collisions.json");
  const json* t = test_named(balls, "impact.head-on");
  ASSERT_NE(t, nullptr);
  std::string output = (*t)["output"].get<std::string>();
  EXPECT_NE(output.find("timed out after 1 s of CPU during time_of_impact"), std::string::npos) << output;
  EXPECT_EQ(output.find("balls_impact"), std::string::npos) << output;
  // The integrators and collisions assignments have a timeout_hint too (an audit's endless loop in
  // midpoint_step read "stepping with k1 is Euler again", the test's hint about wrong numbers).
  for (const std::string assignment : {"collisions", "integrators"}) {
    const std::string hint = read_json(fs::path(kAssignments) / assignment / "assignment.json").at("timeout_hint").get<std::string>();
    if (assignment == "collisions") {
      EXPECT_NE(output.find("This usually means: " + hint), std::string::npos) << output;
      continue;
    }
    const fs::path integrators = with("integrators", "integrators.cpp", "void midpoint_step(const FirstOrderSystem& f, double t, double h, VectorInOut y) {\n",
                                      "void midpoint_step(const FirstOrderSystem& f, double t, double h, VectorInOut y) {\n  for (volatile int spin = 0;; spin = spin + 1) {}\n");
    r = run_motus(dir, {"grade", "integrators", integrators.string(), "--time-limit", "1", "--results",
                        (dir / "integrators.json").string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const json steps = read_json(dir / "integrators.json");
    const json* midpoint = test_named(steps, "midpoint.order");
    ASSERT_NE(midpoint, nullptr);
    const std::string said = (*midpoint)["output"].get<std::string>();
    EXPECT_NE(said.find("timed out after 1 s of CPU"), std::string::npos) << said;
    EXPECT_NE(said.find("This usually means: " + hint), std::string::npos) << said;
  }

  const fs::path cloth = with("cloth", "cloth.cpp", "for (int sweep = 0; sweep < c.iterations; ++sweep) {", "for (;;) {");
  r = run_motus(dir, {"grade", "cloth", cloth.string(), "--time-limit", "1", "--results", (dir / "cloth.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json sheet = read_json(dir / "cloth.json");
  const std::string hint = read_json(fs::path(kAssignments) / "cloth/assignment.json").at("timeout_hint").get<std::string>();
  int with_hint = 0;
  for (const auto& test : sheet.at("tests")) {
    const std::string text = test.at("output").get<std::string>();
    if (text.find("timed out after 1 s") == std::string::npos) continue;
    EXPECT_NE(text.find("This usually means: " + hint), std::string::npos) << text;
    with_hint += text.find("This usually means: " + hint) != std::string::npos;
  }
  EXPECT_GT(with_hint, 0) << sheet.dump(2);
}

// Found by a student-and-instructor audit: one printf("stick %g\n", length) in the cloth solution's
// project_stick timed scene.cloth out (10.4 to 11.2 million lines, 124 to 132 MB, in its 10 s of
// CPU: the server's standard output is unbuffered, each print a write), and the message blamed a
// sweep that never ends, with no word of the printing. It says how much the code printed first,
// counted whole (not the 64 KB the sandbox keeps), and gives the timeout_hint after it as the other
// cause. At --time-limit 1 the same print floods scene.cloth in seconds.
TEST(Grade, ATimeoutAfterAFloodOfPrintsSaysThePrintingFirst) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path submission = copy_solution(dir, "cloth", "cloth-prints");
  std::string source = read_file(submission / "cloth.cpp");
  const std::string find = "const double w = w_a + w_b;";
  const size_t at = source.find(find);
  ASSERT_NE(at, std::string::npos);
  ASSERT_LT(at, source.find("void project_wall"));  // (in project_stick, called for every stick in every sweep)
  source.replace(at, find.size(), "std::printf(\"stick %g\\n\", length);\n  " + find);
  write_file(submission / "cloth.cpp", "#include <cstdio>\n" + source);
  const auto r = run_motus(dir, {"grade", "cloth", submission.string(), "--time-limit", "1", "--results",
                                 (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  const json* cloth = test_named(result, "scene.cloth");
  ASSERT_NE(cloth, nullptr);
  EXPECT_EQ((*cloth)["status"], "failed");
  const std::string output = (*cloth)["output"].get<std::string>();
  std::smatch said;
  ASSERT_TRUE(std::regex_search(output, said, std::regex("^Your code printed ([0-9.]+) (MB|kB) \\(([0-9,]+) lines\\) and timed "
                                                          "out after 1 s of CPU during a run of the scene\\.")))
      << output;
  // All it printed, not what was kept: more than the 100,000 lines a second of the limit that make
  // a flood, and more than the sandbox's 64 KB.
  const long lines = std::stol(std::regex_replace(said[3].str(), std::regex(","), ""));
  EXPECT_GE(lines, 100000) << output;
  EXPECT_EQ(said[2].str(), "MB") << output;
  const std::string hint = read_json(fs::path(kAssignments) / "cloth/assignment.json").at("timeout_hint").get<std::string>();
  const std::string advice = "Printing that much is slow (each print is written out at once, to be shown if the code crashes): "
                             "print less (or only once) and grade again. If it still times out, this usually means: " + hint;
  EXPECT_NE(output.find(advice), std::string::npos) << output;
  EXPECT_EQ(output.find("This usually means"), std::string::npos) << output;  // (the hint only as the other cause)
  // The end of what it printed is still shown, between the two.
  const size_t shown = output.find("The end of its output:\n");
  EXPECT_NE(shown, std::string::npos) << output;
  EXPECT_LT(shown, output.find(advice)) << output;
  EXPECT_NE(output.find("stick 0.1\n", shown), std::string::npos) << output;
}

// The rule itself: a flood is 100,000 lines or 1 MB for each second of the CPU limit, said only of
// an ending out of time (a crash's output is shown, not weighed), and never of a server the busy
// machine starved (the grader's failure, whatever the code printed).
TEST(Grade, OnlyATimeoutAfterAFloodOfPrintsIsSaidToHavePrinted) {
  using namespace motus::grade;
  Limits one, ten;
  one.cpu_seconds = 0.5;  // (counted as 1 s)
  ten.cpu_seconds = 10;
  Ending out;
  out.signal = SIGXCPU;
  out.printed_lines = 99999;
  out.printed_bytes = 99999 * 10;
  EXPECT_EQ(out.describe(one, 1), "timed out after 1 s of CPU");
  out.printed_lines = 100000;
  EXPECT_EQ(out.describe(one, 1), "printed 977 kB (100,000 lines) and timed out after 1 s of CPU");
  EXPECT_EQ(out.describe(ten, 10), "timed out after 10 s of CPU");
  out.printed_lines = 1000000;
  out.printed_bytes = 132u << 20;
  EXPECT_EQ(out.describe(ten, 10), "printed 132 MB (1,000,000 lines) and timed out after 10 s of CPU");
  Ending no_breaks = out;  // (std::cout << x << ' ': many writes, no line break)
  no_breaks.printed_lines = 0;
  no_breaks.printed_bytes = 10u << 20;
  EXPECT_EQ(no_breaks.describe(ten, 10), "printed 10 MB (all on one line) and timed out after 10 s of CPU");
  no_breaks.printed_bytes = (10u << 20) - 1;
  EXPECT_EQ(no_breaks.describe(ten, 10), "timed out after 10 s of CPU");
  Ending waiting = out;
  waiting.signal = SIGKILL;
  waiting.timed_out = true;
  waiting.verdict = WallVerdict::waiting;
  EXPECT_EQ(waiting.describe(ten, 25).rfind("printed 132 MB (1,000,000 lines) and timed out after 25 s waiting, not computing", 0), 0u)
      << waiting.describe(ten, 25);
  waiting.verdict = WallVerdict::starved;
  EXPECT_EQ(waiting.describe(ten, 25).rfind("was not given its 10 s of CPU", 0), 0u) << waiting.describe(ten, 25);
  Ending crash = out;
  crash.signal = SIGSEGV;
  EXPECT_EQ(crash.describe(ten, 3), "was killed by SIGSEGV");
}

// A student's exception is no wrong number: the test's hint (explicit Euler's "moves x with the
// new velocity") followed "threw std::runtime_error: ...", about something else. Numbers the engine
// refused keep theirs (AStepSizeThatShrinksWithoutEndIsTheStudentsErrorWithItsHint). Found by an audit.
TEST(Grade, AStudentsExceptionStopsTheTestWithoutTheNumbersHint) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path submission = solution_with_euler_step_starting(dir, "throws", "throw std::runtime_error(\"not written yet\");",
                                                                "#include <stdexcept>\n");
  ASSERT_FALSE(submission.empty());
  const json test = definitions("integrators").at("euler.table");
  ASSERT_TRUE(test.contains("hint"));
  const fs::path assignment = integrators_with_tests(dir, "table", json::array({test}));
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");  // (kept: test_named points into it)
  const json* t = test_named(result, "euler.table");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ((*t)["status"], "failed");
  const std::string output = (*t)["output"].get<std::string>();
  EXPECT_EQ(output.rfind("Your code stopped the run: ", 0), 0u) << output;
  EXPECT_NE(output.find("threw std::runtime_error: not written yet"), std::string::npos) << output;
  EXPECT_EQ(output.find("This usually means"), std::string::npos) << output;
}

// An order check whose finer runs blow up measures no order: it says which step size's error was
// not finite, rather than an order of −∞ (or one from the coarser runs alone, which would pass).
TEST(Grade, AnOrderCheckWhoseRunBlowsUpSaysWhereAndFails) {
  NEEDS_SANDBOX();
  TempDir dir;
  // euler.order halves h = 0.01 three times; from h = 0.0025 on, this Euler overflows.
  const fs::path submission = solution_with_euler_step_starting(dir, "overflows", "if (h < 0.004) x[0] = 1e300 * 1e300;");
  ASSERT_FALSE(submission.empty());
  const auto r = run_motus(dir, {"grade", "integrators", submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");  // (kept: test_named points into it)
  const json* t = test_named(result, "euler.order");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ((*t)["status"], "failed");
  const std::string output = (*t)["output"].get<std::string>();
  EXPECT_NE(output.find("no order: the error at h = 0.0025 is not finite"), std::string::npos) << output;
  EXPECT_EQ(output.find("global order"), std::string::npos) << output;
}

// An order check reads the order at the two finest halvings, not at the finest alone, and names
// each with its step sizes. Velocityless Verlet with h for h² (seeded_bugs.json) steps x'' = a/h:
// its error at the end is of order 1 and does not shrink, and the ratios of its errors are chance
// — at verlet.order's step sizes, 2^−2.57 and then 2^2.55 at the finest pair. With a tolerance of
// 0.6 the finest pair alone would pass it (and at 0.15 its message was that of a wrong start).
TEST(Grade, AnOrderCheckReadsTheTwoFinestHalvingsAndNamesEachOrder) {
  NEEDS_SANDBOX();
  TempDir dir;
  const auto defs = definitions("integrators");
  json wide = defs.at("verlet.order");
  ASSERT_EQ(wide["dt"], 0.05);
  ASSERT_EQ(wide["halvings"], 3);
  wide["tolerance"] = 0.6;
  const fs::path assignment = integrators_with_tests(dir, "wide", json::array({wide, defs.at("velocity-verlet.order")}));
  const fs::path submission = dir / "h-not-squared";
  fs::create_directories(submission);
  write_file(submission / "integrators.cpp", solution_with({"verlet-h-not-squared"}, {}));
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");  // (kept: test_named points into it)
  EXPECT_EQ(failed(result), (std::set<std::string>{"verlet.order"})) << result.dump(2);
  const json* verlet = test_named(result, "verlet.order");
  const json* velocity_verlet = test_named(result, "velocity-verlet.order");
  ASSERT_TRUE(verlet && velocity_verlet);
  const std::string number = "(-?[0-9.]+(?:e-?[0-9]+)?)";
  const std::regex two_orders("global orders " + number + R"( \(h = 0\.025 to 0\.0125\) and )" + number +
                              R"( \(h = 0\.0125 to 0\.00625\) between successive halvings, from the errors at the end \(h = 0\.05: error)");
  std::smatch m;
  const std::string output = (*verlet)["output"].get<std::string>();
  ASSERT_TRUE(std::regex_search(output, m, two_orders)) << output;
  EXPECT_GT(std::abs(std::stod(m[1].str()) - 2), 0.6) << output;  // the pair that fails it
  EXPECT_LE(std::abs(std::stod(m[2].str()) - 2), 0.6) << output;  // the finest, which alone passed it
  EXPECT_NE(output.find("Expected: order 2 ± 0.6 at each of the 2 finest halvings"), std::string::npos) << output;
  // An order below 0.5 among those read: the step itself is wrong (hint_no_order), said with where.
  EXPECT_NE(output.find("the error does not shrink as h does (order " + m[1].str() + " from h = 0.025 to 0.0125): the step itself is wrong"),
            std::string::npos)
      << output;
  // A test that passes says the orders it read too.
  const std::string passed = (*velocity_verlet)["output"].get<std::string>();
  ASSERT_TRUE(std::regex_search(passed, m, two_orders)) << passed;
  EXPECT_NEAR(std::stod(m[1].str()), 2, 0.01) << passed;
  EXPECT_NEAR(std::stod(m[2].str()), 2, 0.01) << passed;
}

// A stability check whose run's limit is far from the expected one still measures it: that number
// is what tells the student which mistake they made. It said only "at ωh = 1 the run blows up, at
// ωh = 3 it blows up". Symplectic Euler written as explicit Euler (drift with the old velocity)
// grows the oscillator's amplitude by √(1 + z²) a step, z = ωh, so N steps stay within 1000× their
// start only for z ≤ √(1000^(2/N) − 1) (0.118 for the 1,000 steps of these copies of the hidden
// tests); a step that moves nothing (the position-first form, here) never blows up, and the bracket
// stops at its last move, 1½ × 2 × 2¹⁰.
TEST(Grade, AStabilityLimitFarFromTheExpectedOneIsStillMeasured) {
  NEEDS_SANDBOX();
  TempDir dir;
  json tests = json::array();
  for (const char* name : {"symplectic-euler.stability", "symplectic-euler-x.stability"}) {
    json test = definitions("integrators").at(name);
    ASSERT_EQ(test["omega"], 1);
    ASSERT_EQ(test["expect"], 2);
    test["steps"] = 1000;  // (a tenth of the hidden tests': the same kind of limits, in a tenth of the time)
    tests.push_back(test);
  }
  const fs::path assignment = integrators_with_tests(dir, "stability", tests);
  const std::string both = "  v += h * s.acceleration(t, x, v);\n  x += h * v;\n}\n\n"
                           "void symplectic_euler_x_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {\n"
                           "  x += h * v;\n  v += h * s.acceleration(t + h, x, v);\n}\n";
  const fs::path submission = integrators_solution_with(
      dir, "mistaken", both,
      "  const Vector a = s.acceleration(t, x, v);\n  x += h * v;\n  v += h * a;\n}\n\n"
      "void symplectic_euler_x_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {\n"
      "  (void)s, (void)t, (void)h, (void)x, (void)v;\n}\n");
  ASSERT_FALSE(submission.empty());
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");  // (kept: test_named points into it)
  expect_valid_gradescope(result);
  const json* explicit_euler = test_named(result, "symplectic-euler.stability");
  const json* still = test_named(result, "symplectic-euler-x.stability");
  ASSERT_NE(explicit_euler, nullptr);
  ASSERT_NE(still, nullptr);
  EXPECT_EQ((*explicit_euler)["status"], "failed");
  EXPECT_EQ((*still)["status"], "failed");
  const std::string output = (*explicit_euler)["output"].get<std::string>();
  const std::string mark = "largest stable step ωh = ";
  const size_t at = output.find(mark);
  ASSERT_NE(at, std::string::npos) << output;
  const double measured = std::stod(output.substr(at + mark.size()));
  // (12 halvings of the bracket [1/16, 1/8] it moved to: within 2⁻¹⁷ of the limit.)
  EXPECT_NEAR(measured, std::sqrt(std::pow(1000.0, 2.0 / 1000) - 1), 1.0 / (1 << 17)) << output;
  EXPECT_NE(output.find("largest stable step ωh = 2 within 1%"), std::string::npos) << output;
  EXPECT_NE((*still)["output"].get<std::string>().find(
                "the run stays bounded at every step tried, up to ωh = 3072 (1000 steps each)"),
            std::string::npos)
      << (*still)["output"];
}

// A projection check that asks only for the pins fails positions that are not numbers: std::max
// kept 0 against a NaN distance, and a projection that left every body at NaN passed.
TEST(Grade, APinsCheckFailsPositionsThatAreNotNumbers) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path assignment = dir / "pins-only";
  fs::copy(fs::path(kAssignments) / "cloth", assignment, fs::copy_options::recursive);
  fs::remove_all(assignment / "hidden");
  json meta = read_json(assignment / "assignment.json");
  meta.erase("starter_passes");  // (it names tests this copy has not)
  write_file(assignment / "assignment.json", meta.dump(2));
  json test = definitions("cloth").at("pins.hold");
  test["expect"] = {{"pins", 1e-12}};
  write_file(assignment / "tests/public.json", json{{"tests", json::array({test})}}.dump(2));
  write_file(assignment / "rubric.json",
             json{{"tests", json::array({{{"name", "pins.hold"}, {"points", 1}, {"visibility", "visible"}}})}}.dump(2));
  const fs::path submission = copy_solution(dir, "cloth", "nan");
  std::string source = read_file(submission / "cloth.cpp");
  const std::string anchor = "void satisfy_constraints(Bodies& bodies, const Constraints& c) {\n";
  ASSERT_NE(source.find(anchor), std::string::npos);
  // Every body at NaN when it returns (a destructor runs after the solution's own last line).
  source.replace(source.find(anchor), anchor.size(),
                 anchor + "  struct Nan { Bodies& b; ~Nan() { for (int i = 0; i < b.count; ++i) "
                          "b.position(i).setConstant(std::nan(\"\")); } } nan{bodies};\n");
  write_file(submission / "cloth.cpp", "#include <cmath>\n" + source);
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");  // (kept: test_named points into it)
  const json* t = test_named(result, "pins.hold");
  ASSERT_NE(t, nullptr);
  EXPECT_EQ((*t)["status"], "failed") << (*t)["output"];
  EXPECT_NE((*t)["output"].get<std::string>().find("off their pins by up to ∞"), std::string::npos) << (*t)["output"];
}

// A test that counts only with another passed (counts_with_one_of) names a public test of the rubric:
// a hidden one is not run in a student's own grading, and the test could never count there.
TEST(Grade, ATestCountsOnlyWithPublicTestsOfItsRubric) {
  TempDir dir;
  const fs::path assignment = dir / "gated";
  fs::copy(fs::path(kAssignments) / "collisions", assignment, fs::copy_options::recursive);
  const std::string solution = (fs::path(kAssignments) / "collisions/solution").string();
  const std::string tests = read_file(assignment / "tests/public.json");
  const std::string gate = "\"counts_with_one_of\": [\"impact.head-on\", \"impact.chase\"]";
  ASSERT_NE(tests.find(gate), std::string::npos);
  for (const auto& [gates, says] : std::vector<std::pair<std::string, std::string>>{
           {"[\"impulse.3d\"]", "impact.miss: counts_with_one_of: \"impulse.3d\" is not a public test of the rubric"},
           {"[\"impact.miss\"]", "impact.miss: counts_with_one_of: \"impact.miss\" is the test itself"},
           {"[\"no-such-test\"]", "\"no-such-test\" is not a public test of the rubric"},
           {"[]", "counts_with_one_of: names no test"}}) {
    std::string changed = tests;
    changed.replace(changed.find(gate), gate.size(), "\"counts_with_one_of\": " + gates);
    write_file(assignment / "tests/public.json", changed);
    fs::remove(dir / "r.json");  // (a grading that cannot start still writes a results file saying why)
    const auto r = run_motus(dir, {"grade", assignment.string(), solution, "--results", (dir / "r.json").string()});
    EXPECT_EQ(r.status, 2) << gates << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  }
}

// scores.csv is CSV whatever the students named their folders: a comma or a quote is quoted,
// and a name a spreadsheet would run as a formula opens as text.
TEST(Grade, TheScoresAreCsvWhateverTheFoldersAreCalled) {
  NEEDS_SANDBOX();
  TempDir dir;
  for (const char* name : {"smith, john", "say \"hi\"", "=1+1"}) fs::create_directories(dir / "batch" / name);
  const auto r = run_motus(dir, {"grade", "integrators", "--batch", (dir / "batch").string(), "--out",
                                 (dir / "results").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string csv = read_file(dir / "results/scores.csv");
  EXPECT_EQ(csv, r.out);
  for (const char* row : {"\n'=1+1,0,", "\n\"say \"\"hi\"\"\",0,", "\n\"smith, john\",0,"})
    EXPECT_NE(csv.find(row), std::string::npos) << row << " in:\n" << csv;
  EXPECT_EQ(count_lines(csv), 4) << csv;
}

TEST(Grade, AnAssignmentGivenByARelativePathGradesAsByItsFullPath) {
  // The sandbox mounts the assignment's provided files by their path: a relative one once made
  // the build fail, and the student lost every point for the grader's mistake.
  NEEDS_SANDBOX();
  TempDir dir;
  fs::copy(fs::path(kAssignments) / "integrators", dir / "mine", fs::copy_options::recursive);
  // motus starts where this test is: in `dir`, for the time of the run.
  const fs::path was = fs::current_path();
  fs::current_path(dir.path());
  const auto r = run_motus(dir, {"grade", "mine", (fs::path(kAssignments) / "integrators/solution").string(), "--results",
                                 (dir / "r.json").string()});
  fs::current_path(was);
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "r.json");
  EXPECT_TRUE(failed(result).empty()) << result.dump(2);
  EXPECT_GT(result["score"].get<double>(), 0);
  EXPECT_EQ(result["score"], result["max_score"]);
}

TEST(Grade, WithoutASandboxItRefusesUnlessToldAndThenStillGrades) {
  TempDir dir;
  const std::string solution = (fs::path(kAssignments) / "integrators/solution").string();
  auto r = run_motus(dir, {"grade", "integrators", solution}, {"MOTUS_BWRAP=/nonexistent/bwrap"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_EQ(count_lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("--no-sandbox"), std::string::npos) << r.err;
  r = run_motus(dir, {"grade", "integrators", solution, "--no-sandbox", "--results", (dir / "r.json").string()},
                {"MOTUS_BWRAP=/nonexistent/bwrap"});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "r.json");
  EXPECT_EQ(result["score"], result["max_score"]) << r.out;
}

TEST(Grade, AnInternalFailureStillLeavesAValidResultThatSaysSo) {
  NEEDS_SANDBOX();
  TempDir dir;
  const auto r = run_motus(dir, {"grade", "integrators", (fs::path(kAssignments) / "integrators/solution").string(),
                                 "--results", (dir / "results.json").string()},
                           {"MOTUS_GRADE_FAIL=1"});
  EXPECT_EQ(r.status, 1) << r.err;
  const json result = read_json(dir / "results.json");
  expect_valid_gradescope(result);
  EXPECT_NE(result["output"].get<std::string>().find("could not finish"), std::string::npos);
}

// Found by an audit: without --hidden the package said "the rubric's 11 hidden tests are left out",
// where the rubric has 2 of visibility hidden and 9 after_due_date ("hidden" in two senses; the
// grading's summary says "9 shown after the due date, 2 never shown"). It counts them as that does.
TEST(Grade, APackageWithoutHiddenSaysWhichTestsItLeavesOutAndWhenTheyAreShown) {
  TempDir dir;
  std::set<std::string> public_tests;
  for (const auto& entry : fs::directory_iterator(fs::path(kAssignments) / "integrators/tests"))
    if (entry.path().extension() == ".json") {
      const json file = read_json(entry.path());
      for (const auto& t : file["tests"]) public_tests.insert(t["name"].get<std::string>());
    }
  long left_out = 0, later = 0;
  double out_of = 0;
  const json rubric = read_json(fs::path(kAssignments) / "integrators/rubric.json");
  for (const auto& t : rubric["tests"]) {
    if (public_tests.count(t["name"].get<std::string>())) {
      out_of += t["points"].get<double>();
      continue;
    }
    ++left_out;
    later += t["visibility"] == "after_due_date" || t["visibility"] == "after_published";
  }
  ASSERT_GT(later, 0);
  ASSERT_GT(left_out - later, 0);
  const auto r = run_motus(dir, {"grade", "integrators", "--package", "gradescope", "--out", (dir / "autograder.zip").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "motus: note: no --hidden: the autograder grades the public tests only; " + std::to_string(left_out) +
                       " of the rubric's tests are not among them (the instructor's, given with --hidden: " + std::to_string(later) +
                       " shown after the due date, " + std::to_string(left_out - later) +
                       " never shown) and are left out; the scores are then out of " + fmt_points(out_of) + " points\n");
  // The grading's own summary counts them the same way.
  if (!sandbox_available()) return;
  fs::create_directories(dir / "empty");
  const auto graded = run_motus(dir, {"grade", "integrators", (dir / "empty").string()});
  EXPECT_NE(graded.out.find("(" + std::to_string(left_out) + " of the instructor's tests not run here: " + std::to_string(later) +
                            " shown after the due date, " + std::to_string(left_out - later) + " never shown)"),
            std::string::npos)
      << graded.out;
}

// One never-shown test not run: "1 hidden test", not "1 hidden tests".
TEST(Grade, OneHiddenTestNotRunIsSaidInTheSingular) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path assignment = integrators_with_tests(dir, "one", json::array({definitions("integrators").at("euler.table")}));
  json rubric = read_json(assignment / "rubric.json");
  rubric["tests"].push_back({{"name", "secret"}, {"points", 1}, {"visibility", "hidden"}});
  write_file(assignment / "rubric.json", rubric.dump(2));
  fs::create_directories(dir / "empty");
  const auto graded = run_motus(dir, {"grade", assignment.string(), (dir / "empty").string()});
  EXPECT_NE(graded.out.find("(1 hidden test not run here)"), std::string::npos) << graded.out << graded.err;
}

TEST(Grade, TheGradescopeZipGradesTheSolutionToFullMarks) {
  NEEDS_SANDBOX();
  TempDir dir;
  auto r = run_motus(dir, {"grade", "integrators", "--package", "gradescope", "--out", (dir / "autograder.zip").string(),
                           "--hidden", hidden("integrators")});
  ASSERT_EQ(r.status, 0) << r.err;
  // Gradescope's layout, in a temporary root: the zip in source/, the submission in submission/.
  const fs::path root = dir / "autograder";
  fs::create_directories(root / "source");
  r = run_program(dir, "/usr/bin/unzip", {"-q", (dir / "autograder.zip").string(), "-d", (root / "source").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* f : {"setup.sh", "run_autograder", "motus/CMakeLists.txt", "motus/debian-packages.txt",
                        "assignment/rubric.json", "hidden/hidden.json"})
    EXPECT_TRUE(fs::exists(root / "source" / f)) << f;
  EXPECT_NE(read_file(root / "source/setup.sh").find("debian-packages.txt"), std::string::npos);
  // setup.sh installs debian-packages.txt (the one list) but the packages only motus's tests,
  // benchmarks and fuzzers need: it ran with stand-ins for apt-get and cmake first on PATH, which
  // write down what they were asked. (It installed chromium, clang, libFuzzer, GoogleTest… for a
  // build that finds none of them.)
  {
    const fs::path bin = dir / "stand-ins", asked = dir / "asked.txt";
    fs::create_directories(bin);
    for (const char* program : {"apt-get", "cmake"}) {
      write_file(bin / program, "#!/bin/sh\necho \"" + std::string(program) + " $*\" >> '" + asked.string() + "'\n");
      fs::permissions(bin / program, fs::perms::owner_all);
    }
    const auto setup = run_program(dir, (root / "source/setup.sh").string(), {}, {"PATH=" + bin.string() + ":/usr/bin:/bin"});
    ASSERT_EQ(setup.status, 0) << setup.out << setup.err;
    std::vector<std::string> listed, installed;
    {
      std::istringstream list(read_file(root / "source/motus/debian-packages.txt")), line(read_file(asked));
      for (std::string name; list >> name;) listed.push_back(name);
      std::string words;
      for (std::string l; std::getline(line, l);)
        if (l.starts_with("apt-get install ")) words = l;
      std::istringstream install(words);
      for (std::string word; install >> word;)
        if (word != "apt-get" && word != "install" && !word.starts_with("-")) installed.push_back(word);
    }
    const std::set<std::string> test_only = {"chromium",     "clang",        "libfuzzer-14-dev", "libclang-rt-14-dev",
                                             "libgtest-dev", "libgmock-dev", "libbenchmark-dev", "python3-jsonschema"};
    std::vector<std::string> expected;
    for (const auto& name : listed)
      if (!test_only.count(name)) expected.push_back(name);
    EXPECT_EQ(installed, expected) << read_file(asked);
    for (const auto& name : test_only)  // (each is in the list: a rename there would install it again)
      EXPECT_NE(std::find(listed.begin(), listed.end(), name), listed.end()) << name;
    // What the motus target's configuration finds (find_package, pkg_check_modules), and grading needs.
    for (const char* needed : {"build-essential", "cmake", "pkg-config", "libeigen3-dev", "libcli11-dev", "nlohmann-json3-dev",
                               "libfmt-dev", "libbox2d-dev", "libbullet-dev", "libosmesa6-dev", "libpng-dev", "libfreetype-dev",
                               "libboost-dev", "libmuparser-dev", "bubblewrap"})
      EXPECT_NE(std::find(installed.begin(), installed.end(), needed), installed.end()) << needed;
    EXPECT_NE(read_file(asked).find("cmake --build motus/build"), std::string::npos) << read_file(asked);
    // A warning, not a failure, on an image other than Debian 12, the only one it was tried on.
    const std::string os = read_file("/etc/os-release");
    const bool debian_12 = os.find("\nID=debian\n") != std::string::npos && os.find("\nVERSION_ID=\"12\"\n") != std::string::npos;
    EXPECT_EQ(setup.err.find("setup.sh: warning: this image is "), debian_12 ? std::string::npos : 0u) << setup.err;
    EXPECT_NE(read_file(root / "source/setup.sh").find("not Debian 12 (bookworm), the only"), std::string::npos);
  }
  // No reference solution and no hidden tests but the ones it grades with (a student's code may
  // run in this image without the sandbox).
  for (const auto& e : fs::recursive_directory_iterator(root / "source"))
    EXPECT_TRUE(e.path().filename() != "solution" && (e.path().filename() != "hidden" || e.path() == root / "source/hidden"))
        << e.path();
  // setup.sh's build: the zip's sources configure as setup.sh configures them (every folder
  // the top CMakeLists.txt adds is there).
  r = run_program(dir, "/usr/bin/cmake", {"-S", (root / "source/motus").string(), "-B", (dir / "zip-build").string(),
                                          "-DCMAKE_BUILD_TYPE=Release", "-DBUILD_TESTING=OFF", "-DMOTUS_BUILD_BENCH=OFF"});
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  fs::create_directories(root / "submission");
  fs::copy_file(fs::path(kAssignments) / "integrators/solution/integrators.cpp", root / "submission/integrators.cpp");
  r = run_program(dir, (root / "source/run_autograder").string(), {},
                  {"AUTOGRADER_ROOT=" + root.string(), std::string("MOTUS_BINARY=") + kMotus});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(root / "results/results.json");
  expect_valid_gradescope(result);
  double max = 0;
  for (const auto& [name, pts] : points("integrators")) max += pts;
  EXPECT_EQ(result["score"].get<double>(), max);
  // The hidden tests are the grader's alone once it has run.
  for (const auto& e : fs::recursive_directory_iterator(root / "source/hidden"))
    EXPECT_EQ(fs::status(e.path()).permissions() & (fs::perms::group_all | fs::perms::others_all), fs::perms::none) << e.path();
  EXPECT_EQ(fs::status(root / "source/hidden").permissions() & (fs::perms::group_all | fs::perms::others_all), fs::perms::none);
}

TEST(Grade, EachTestHasTheWholeCpuLimitOfItsOwn) {
  // Five copies of one test, and an euler_step that spends 0.15 s of CPU on every call: 0.75 s a
  // test, well within the 3 s limit (of CPU; its wall clock is a backstop of 11 s), but
  // 3.75 s in all. Each test's limit is its own (docs/grading.md), not what the tests before it
  // left over.
  NEEDS_SANDBOX();
  TempDir dir;
  json test = definitions("integrators").at("euler.table");
  json tests = json::array();
  for (int i = 1; i <= 5; ++i) {
    test["name"] = "euler.table-" + std::to_string(i);
    tests.push_back(test);
  }
  const fs::path assignment = integrators_with_tests(dir, "five", tests);
  const fs::path submission = solution_with_euler_step_starting(
      dir, "slow", "for (const std::clock_t until = std::clock() + CLOCKS_PER_SEC * 3 / 20; std::clock() < until;) {}",
      "#include <ctime>\n");
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--time-limit", "3", "--results",
                                 (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  expect_valid_gradescope(result);
  EXPECT_TRUE(failed(result).empty()) << result.dump(2);
  EXPECT_EQ(result["score"].get<double>(), 5);
}

// A test whose scene has an equations system runs in the sandbox too: muparser comes from motus's
// expressions module, which the sandbox holds only because the grader mounts it beside motus.
// RK4 on Lorenz written as expressions is fourth order, as on the compiled Lorenz (the hidden
// test rk4.lorenz-order, its expect and tolerance).
TEST(Grade, ATestOnAnEquationsSceneRunsInTheSandbox) {
  NEEDS_SANDBOX();
  TempDir dir;
  json test = definitions("integrators").at("rk4.lorenz-order");
  ASSERT_EQ(test["scene"], "lorenz");
  test["scene"] = "lorenz_equations";
  const fs::path assignment = integrators_with_tests(dir, "equations", json::array({test}));
  const fs::path submission = copy_solution(dir, "integrators", "solution");
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  expect_valid_gradescope(result);
  EXPECT_TRUE(failed(result).empty()) << result.dump(2);
  EXPECT_EQ(result["score"].get<double>(), 1);
}

}  // namespace

namespace {

// `motus serve` (the student's side of the grader) refuses a request in other than 1, 2 or 3
// dimensions: the parts' pins and walls hold three numbers, and 64 were written past them (and
// what lay beyond was read back into the answer).
TEST(Serve, RequestsInMoreThanThreeDimensionsAreRefused) {
  TempDir dir;
  // One request to `motus serve --plugin PLUGIN`: its one answer.
  auto serve = [&](const std::string& plugin, const std::string& request) {
    write_file(dir / "request.txt", request + "\n");
    MotusFiles files;
    files.in = (dir / "request.txt").string();
    files.out = (dir / "answer.txt").string();
    files.err = (dir / "err.txt").string();
    const int raw = run_motus_with({"serve", "--plugin", kAssignmentPlugins + "/" + plugin}, files);
    EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << read_file(dir / "err.txt");
    const std::string said = read_file(dir / "answer.txt");  // (its first line: it serves)
    const std::string serving = std::string(motus::grade::wire::kServing) + "\n";
    EXPECT_EQ(said.substr(0, serving.size()), serving);
    return said.substr(std::min(said.size(), serving.size()));
  };
  std::string many = "[0";
  for (int k = 1; k < 64; ++k) many += ",0";
  many += "]";
  const std::string projected = serve("cloth-solution.so", R"({"op":"project","dimensions":64,"inverse_mass":[1],"radius":[1],"x":)" + many +
                                                             R"(,"sticks":[],"pins":[[0,)" + many + R"(]],"walls":[[)" + many + R"(,0]]})");
  EXPECT_EQ(projected, "{\"error\":\"dimensions: 1, 2 or 3 dimensions, not 64\",\"ok\":false}\n");
  const std::string collided = serve("collisions-solution.so",
                                     R"({"op":"collide_balls","v_a":[1,0,0,0],"v_b":[0,0,0,0],"m_a":1,"m_b":1,"n":[1,0,0,0],"e":1})");
  EXPECT_EQ(collided, "{\"error\":\"v_a: 1, 2 or 3 dimensions, not 4\",\"ok\":false}\n");
}

}  // namespace

namespace {

// A handed-in file that is not where the handout says, as students hand them in: the files test
// says where it is (under another case, in a folder, packed), and a zip given as the submission
// is refused saying to unpack it.
// The summary on the terminal says a failed test's output once when the next ones say the same: a
// submission that does not compile printed "Not run: the submission does not compile (see
// \"build\")." under every one of its twenty-odd tests (a student audit).
TEST(Grade, TheSummarySaysARepeatedOutputOnce) {
  motus::grade::GradeResult r;
  r.output = "0 of 3 points";
  const std::string not_run = "Not run: the submission does not compile (see \"build\").";
  const auto failed_test = [](std::string name, std::string number, std::string title, std::string output) {
    motus::grade::TestResult t;
    t.name = std::move(name), t.number = std::move(number), t.title = std::move(title), t.output = std::move(output);
    t.max_score = 1;
    return t;
  };
  r.tests = {failed_test("build", "1", "the submission compiles", "main.cpp:1: error: expected ';'"),
             failed_test("euler.table", "2", "the table", not_run), failed_test("rk4.order", "3", "fourth order", not_run),
             failed_test("verlet.order", "4", "second order", "a different reason")};
  const std::string text = motus::grade::text_summary(r);
  EXPECT_EQ(text.find(not_run), text.rfind(not_run)) << text;  // once
  EXPECT_NE(text.find("rk4.order: fourth order\n             (as above)\n"), std::string::npos) << text;
  EXPECT_NE(text.find("verlet.order: second order\n             a different reason\n"), std::string::npos) << text;
  EXPECT_NE(text.find("euler.table: the table\n             " + not_run + "\n"), std::string::npos) << text;
}

TEST(Grade, AMissingFileSaysWhereItMightBe) {
  NEEDS_SANDBOX();  // (grade makes its sandbox before it looks at the files: without one, exit 2)
  TempDir dir;
  const std::string solution = read_file(fs::path(kAssignments) / "integrators/solution/integrators.cpp");
  fs::create_directories(dir / "case");
  write_file(dir / "case/Integrators.cpp", solution);
  fs::create_directories(dir / "folder/integrators");
  write_file(dir / "folder/integrators/integrators.cpp", solution);
  fs::create_directories(dir / "packed");
  write_file(dir / "packed/integrators.zip", "PK");
  // Two folders down (as a zip unpacked with its own folder in it): only one down was looked at.
  fs::create_directories(dir / "deeper/hw3/src");
  write_file(dir / "deeper/hw3/src/integrators.cpp", solution);
  const std::map<std::string, std::string> hints = {
      {"case", "there is Integrators.cpp: names are case-sensitive"},
      {"folder", "there is integrators/integrators.cpp: put it at the top"},
      {"deeper", "there is hw3/src/integrators.cpp: put it at the top"},
      {"packed", "there is integrators.zip: hand in the files themselves, unpacked"}};
  for (const auto& [folder, hint] : hints) {
    const auto r = run_motus(dir, {"grade", "integrators", (dir / folder).string(), "--results",
                                   (dir / (folder + ".json")).string()});
    ASSERT_EQ(r.status, 0) << r.err;
    const json result = read_json(dir / (folder + ".json"));
    const json* files = test_named(result, "files");
    ASSERT_NE(files, nullptr) << folder;
    EXPECT_NE((*files)["output"].get<std::string>().find("integrators.cpp: missing (" + hint), std::string::npos)
        << folder << ": " << (*files)["output"];
  }
  const auto zip = run_motus(dir, {"grade", "integrators", (dir / "packed/integrators.zip").string()});
  EXPECT_EQ(zip.status, 2);
  EXPECT_NE(zip.err.find("is a file; a submission is the folder of the handout's files (unpack it first)"),
            std::string::npos) << zip.err;
  // The handout's file itself, not its folder (a student audit): the folder to give is named.
  fs::create_directories(dir / "mine");
  write_file(dir / "mine/integrators.cpp", "");
  const auto file = run_motus(dir, {"grade", "integrators", (dir / "mine/integrators.cpp").string()});
  EXPECT_EQ(file.status, 2);
  EXPECT_NE(file.err.find("mine/integrators.cpp: is a file; a submission is the folder of the handout's files (give the "
                          "folder that holds it: " + (dir / "mine").string() + ")"),
            std::string::npos) << file.err;
}

// ---------------------------------------------------------------------------------------------------
// Fair timing (docs/grading.md, "The limits"): the CPU limit decides whether the student's code was
// too slow; the wall clock is a backstop with room for a wait for a core, and a process starved at
// it by a busy machine is the grader's failure. Found by an audit: 32 copies of the solution graded
// with --jobs 32 on 2 cores all scored 0 ("the compiler timed out after 90.6 s"), and a solution
// that takes 6 s of a 10 s limit failed ("timed out after 10 s") whenever the machine was loaded.

motus::grade::TimeUse used(double wall, double cpu, double run_delay, bool known = true) {
  motus::grade::TimeUse u;
  u.wall = wall, u.cpu = cpu, u.run_delay = run_delay, u.run_delay_known = known;
  return u;
}

TEST(Grade, TheWallClockBackstopIsTwiceTheCpuLimitAndFiveSeconds) {
  using namespace motus::grade;
  EXPECT_DOUBLE_EQ(wall_backstop(10), 25);   // a test's, at the default limit
  EXPECT_DOUBLE_EQ(wall_backstop(2), 9);
  EXPECT_DOUBLE_EQ(wall_backstop(60), 125);  // the compiler's
  EXPECT_DOUBLE_EQ(cpu_limit_seconds(0.5), 1);  // RLIMIT_CPU counts whole seconds
  EXPECT_DOUBLE_EQ(cpu_limit_seconds(10), 10);
}

TEST(Grade, AProcessAtItsWallBackstopIsJudgedByWhatItDidWithItsTime) {
  using namespace motus::grade;
  // The audit's batch: a compiler that had 8 s of CPU in 125 s and waited 110 s for a core.
  EXPECT_EQ(judge_wall_timeout(used(125, 8, 110), 60), WallVerdict::starved);
  // A test of 10 s that had a sixteenth of a core (32 jobs on 2 cores).
  EXPECT_EQ(judge_wall_timeout(used(25, 1.5, 23), 10), WallVerdict::starved);
  // Runnable half the time, exactly: starved; a little less: waiting.
  EXPECT_EQ(judge_wall_timeout(used(25, 4, 8.5), 10), WallVerdict::starved);
  EXPECT_EQ(judge_wall_timeout(used(25, 4, 8.4), 10), WallVerdict::waiting);
  // A submission that stops reading its input: asleep, no CPU, no wait for a core.
  EXPECT_EQ(judge_wall_timeout(used(9, 0.05, 0.01), 2), WallVerdict::waiting);
  // It computed 8 s of its 10, then blocked for good.
  EXPECT_EQ(judge_wall_timeout(used(25, 8, 0.5), 10), WallVerdict::waiting);
  // Its CPU used up (the compiler's processes have a limit each: together they can pass it).
  EXPECT_EQ(judge_wall_timeout(used(125, 61, 40), 60), WallVerdict::used_its_cpu);
  EXPECT_EQ(judge_wall_timeout(used(25, 10, 0), 10), WallVerdict::used_its_cpu);
  // It made itself nicer than the grader (or SCHED_IDLE), and so was not run: its own doing.
  TimeUse nicer = used(25, 0.2, 24);
  nicer.lowered_priority = true;
  EXPECT_EQ(judge_wall_timeout(nicer, 10), WallVerdict::lowered_its_priority);
  // Without schedstat: runnable when measured, the time it did not compute was a wait for a core.
  TimeUse unknown = used(25, 1, 0, false);
  unknown.runnable_now = true;
  EXPECT_EQ(judge_wall_timeout(unknown, 10), WallVerdict::starved);
  unknown.runnable_now = false;
  EXPECT_EQ(judge_wall_timeout(unknown, 10), WallVerdict::waiting);
  // What the grader's failure then says: what it got, and what to do.
  const std::string said = starved_message("the compiler", used(125, 8, 110), 60);
  EXPECT_EQ(said.rfind("the machine was too busy to give the compiler its 60 s of CPU (in 125 s it had 8 s of CPU and "
                       "waited 110 s for a core): not the submission's fault; grade it again with fewer --jobs (this machine has ", 0),
            0u)
      << said;
}

// Code that waits 1.5 s (no CPU) in its first call, under a 1 s limit: the wall clock is no longer
// the limit (its backstop is 7 s), and its CPU is well within 1 s. It timed out before.
TEST(Grade, ATestsWallClockIsABackstopWithRoomBeyondItsCpuLimit) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path assignment = integrators_with_tests(dir, "one", json::array({definitions("integrators").at("euler.table")}));
  const fs::path submission = solution_with_euler_step_starting(
      dir, "waits", "static bool waited = false; if (!waited) { waited = true; ::usleep(1500000); }", "#include <unistd.h>\n");
  ASSERT_FALSE(submission.empty());
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--time-limit", "1", "--results",
                                 (dir / "results.json").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  const json result = read_json(dir / "results.json");
  expect_valid_gradescope(result);
  EXPECT_TRUE(failed(result).empty()) << result.dump(2);
  EXPECT_EQ(result["score"].get<double>(), 1);
}

// A test's server starved by a busy machine: once the test's server has started, it is pinned to one
// core, on which a process of nice -20 (in a scheduling autogroup of nice -20: the sandbox's
// session is an autogroup of its own) spins. The server, which needs 0.5 s of CPU of its 1 s, gets
// about 1 % of the core: at the backstop (7 s) it had little CPU and waited nearly all the time
// for the core. The grader's failure: exit 1, and a results file that says so (before, "timed out
// after 1 s", the student's 0).
bool descends_from(pid_t pid, pid_t ancestor) {
  for (int hops = 0; pid > 1 && hops < 16; ++hops) {
    if (pid == ancestor) return true;
    const std::string stat = read_file("/proc/" + std::to_string(pid) + "/stat");
    const size_t after = stat.rfind(')');
    if (after == std::string::npos) return false;
    pid = static_cast<pid_t>(std::strtol(stat.c_str() + after + 4, nullptr, 10));  // (") S PPID")
  }
  return false;
}

pid_t server_of(pid_t grader) {
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string name = entry.path().filename().string();
    if (!std::all_of(name.begin(), name.end(), ::isdigit)) continue;
    std::string command = read_file(entry.path() / "cmdline");
    std::replace(command.begin(), command.end(), '\0', ' ');
    if (command.find("/motus/motus serve --plugin") == 0 && descends_from(std::stoi(name), grader)) return std::stoi(name);
  }
  return -1;
}

// The last of the cores this process may run on, as a set of one (the busy-machine tests' core).
cpu_set_t last_core() {
  cpu_set_t all, one;
  CPU_ZERO(&one);
  if (::sched_getaffinity(0, sizeof all, &all) != 0) return one;
  int core = -1;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &all)) core = c;
  if (core >= 0) CPU_SET(core, &one);
  return one;
}

// A process that spins for ever on `core` at nice -20, in a scheduling autogroup of nice -20 (a
// sandbox's session is an autogroup of its own): what runs beside it there gets about 1 % of the
// core. Needs root; the caller kills it (SIGKILL, then waitpid).
pid_t start_hog(const cpu_set_t& core) {
  const pid_t hog = ::fork();
  if (hog == 0) {
    ::sched_setaffinity(0, sizeof core, &core);
    ::setpriority(PRIO_PROCESS, 0, -20);
    std::ofstream("/proc/self/autogroup") << "-20";
    volatile long spin = 0;
    for (;;) spin = spin + 1;
  }
  return hog;
}

TEST(Grade, AServerStarvedOfItsCpuByABusyMachineIsTheGradersFailure) {
  NEEDS_SANDBOX();
  if (::geteuid() != 0) GTEST_SKIP() << "needs root, for a process of nice -20 that the server cannot outrun";
  TempDir dir;
  const fs::path assignment = integrators_with_tests(dir, "one", json::array({definitions("integrators").at("euler.table")}));
  const fs::path submission = solution_with_euler_step_starting(
      dir, "computes",
      // (A second's sleep first: the test's head start to find the server and pin it beside the
      // hog. Spinning at once, a test held off the CPU for half a second found code already done.)
      "static bool done = false; if (!done) { done = true; ::usleep(1000000); "
      "for (const std::clock_t until = std::clock() + CLOCKS_PER_SEC / 2; std::clock() < until;) {} }",
      "#include <ctime>\n#include <unistd.h>\n");
  ASSERT_FALSE(submission.empty());
  const cpu_set_t one = last_core();
  ASSERT_EQ(CPU_COUNT(&one), 1);
  MotusFiles files;
  files.err = (dir / "err.txt").string();
  files.folder = dir.path().string();
  const pid_t grader = start_motus_with({"grade", assignment.string(), submission.string(), "--time-limit", "1",
                                         "--results", (dir / "results.json").string()},
                                        files);
  ASSERT_GT(grader, 0);
  pid_t server = -1;
  for (int i = 0; i < 24000 && server < 0; ++i) {  // (the build first: up to 120 s)
    server = server_of(grader);
    if (server < 0) ::usleep(2000);
  }
  pid_t hog = -1;
  if (server > 0) {
    hog = start_hog(one);
    std::error_code error;  // (the server's threads, and the processes it is in)
    for (const auto& task : fs::directory_iterator("/proc/" + std::to_string(server) + "/task", error))
      ::sched_setaffinity(static_cast<pid_t>(std::stoi(task.path().filename().string())), sizeof one, &one);
  }
  int raw = 0;
  const bool ended = ended_within(grader, 120, raw);
  if (hog > 0) {
    ::kill(hog, SIGKILL);
    ::waitpid(hog, nullptr, 0);
  }
  ASSERT_GT(server, 0) << "no server seen: " << read_file(dir / "err.txt");
  ASSERT_TRUE(ended) << read_file(dir / "err.txt");
  const std::string err = read_file(dir / "err.txt");
  EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 1) << raw << ": " << err;
  EXPECT_NE(err.find("test euler.table: the machine was too busy to give the student's code its 1 s of CPU (in "), std::string::npos)
      << err;
  EXPECT_NE(err.find("grade it again with fewer --jobs"), std::string::npos) << err;
  const json result = read_json(dir / "results.json");
  EXPECT_EQ(result["extra_data"]["internal_error"], true) << result.dump(2);
  EXPECT_NE(result["output"].get<std::string>().find("the machine was too busy"), std::string::npos) << result.dump(2);
}

// A process that waited for a core and ended before the deadline: its wait counts. The sandbox
// runs a shell whose child spins for 6 s of wall time on a core that a process of nice -20 holds
// (so it gets about 1 % of it, and waits the rest), then ends and is reaped, and the shell sleeps
// on to the deadline (7 s, a CPU limit of 1 s's backstop). The deadline sees a sleeping shell; the
// child's wait left /proc with it, and the verdict was "waiting, not computing": the student's 0
// for a compile that a machine busy with two builds held up (cc1plus waits, ends, is reaped by
// g++; the assembler is what is left at the deadline). Sampled while it runs, it is a busy machine.
TEST(Grade, AWaitForACoreByAProcessThatHasEndedCountsAtTheDeadline) {
  NEEDS_SANDBOX();
  if (::geteuid() != 0) GTEST_SKIP() << "needs root, for a process of nice -20 that the sandbox cannot outrun";
  using namespace motus::grade;
  cpu_set_t all;
  ASSERT_EQ(::sched_getaffinity(0, sizeof all, &all), 0);
  const cpu_set_t one = last_core();
  ASSERT_EQ(CPU_COUNT(&one), 1);
  const pid_t hog = start_hog(one);
  ASSERT_GT(hog, 0);
  ::usleep(200000);  // (the hog on its core first)
  Ending ending;
  {
    ASSERT_EQ(::sched_setaffinity(0, sizeof one, &one), 0);  // (the sandbox inherits it)
    SandboxUser user;
    SandboxSpec spec;
    spec.argv = {"/usr/bin/sh", "-c", "timeout 6 sh -c 'while :; do :; done'; exec sleep 100"};
    spec.uid = user.uid();
    Limits limits;
    limits.cpu_seconds = 1;
    SandboxProcess process(spec, limits);
    ::sched_setaffinity(0, sizeof all, &all);
    ending = process.finish(std::chrono::steady_clock::now() + std::chrono::seconds(7));
  }
  ::kill(hog, SIGKILL);
  ::waitpid(hog, nullptr, 0);
  ASSERT_TRUE(ending.timed_out);
  ASSERT_TRUE(ending.use.run_delay_known) << "no schedstat on this kernel";
  // The child waited nearly all its 6 s (the sleeping shell and sleep wait for nothing).
  EXPECT_GT(ending.use.run_delay, 4.0) << "cpu " << ending.use.cpu << " s, wall " << ending.use.wall << " s";
  EXPECT_EQ(judge_wall_timeout(ending.use, 1), WallVerdict::starved)
      << "cpu " << ending.use.cpu << " s, waited " << ending.use.run_delay << " s, wall " << ending.use.wall << " s";
}

// The sandbox's root is bubblewrap's own tmpfs, unsized: writable, code in the test's server wrote
// 960 MB of files beside /box/student.so, past its memory limit of 512 MB (and a million empty
// files there would hold the kernel's memory as they did in /tmp). Only /tmp and the mounts made
// writable can be written.
TEST(Grade, TheSandboxsRootCannotBeWritten) {
  NEEDS_SANDBOX();
  using namespace motus::grade;
  TempDir dir;
  fs::create_directories(dir / "out");
  SandboxUser user;
  if (!unreachable_for(user.uid(), (dir / "out").string()).empty()) GTEST_SKIP() << "the sandbox's user cannot reach " << dir.path();
  if (::geteuid() == 0) ::chown((dir / "out").c_str(), user.uid(), static_cast<gid_t>(-1));
  // Each write, in a shell of its own, and its exit status: 0 written, else refused.
  auto write_in_sandbox = [&](const std::string& file) {
    SandboxSpec spec;
    spec.argv = {"/usr/bin/sh", "-c", "echo x > " + file};
    spec.mounts = {{(dir / "out").string(), "/out", true}};
    spec.uid = user.uid();
    SandboxProcess process(spec, Limits{});
    const Ending e = process.finish(std::chrono::steady_clock::now() + std::chrono::seconds(20));
    EXPECT_TRUE(e.exited) << file;
    return e.status;
  };
  EXPECT_NE(write_in_sandbox("/x"), 0) << "the root";
  EXPECT_NE(write_in_sandbox("/out2"), 0) << "the root, beside a mount";
  EXPECT_EQ(write_in_sandbox("/tmp/x"), 0) << "/tmp";
  EXPECT_EQ(write_in_sandbox("/out/x"), 0) << "a writable mount";
  EXPECT_TRUE(fs::exists(dir / "out/x"));
}

// `submission` graded against a copy of the integrators assignment whose one test is euler.table,
// with a CPU limit of 1 s: its valid results.json (the grading ends with exit status 0).
json graded_on_the_euler_table(const TempDir& dir, const fs::path& submission) {
  const fs::path assignment = integrators_with_tests(dir, "one", json::array({definitions("integrators").at("euler.table")}));
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--time-limit", "1", "--results",
                                 (dir / "results.json").string()});
  EXPECT_EQ(r.status, 0) << r.err;
  if (r.status != 0 || !fs::exists(dir / "results.json")) return json::object();
  const json result = read_json(dir / "results.json");
  expect_valid_gradescope(result);
  return result;
}

// A process's threads waiting for each other's cores are its own doing: each process counts its
// longest-waiting thread, and processes one after another (a compile's) each their own.
TEST(Grade, AProcesssThreadsWaitingForEachOtherCountAsOneWait) {
  using namespace motus::grade;
  TaskWaits waits;
  waits[10] = {10, 2.0};  // a process of three threads, 3 s the longest wait
  waits[11] = {10, 3.0};
  waits[12] = {10, 1.0};
  waits[20] = {20, 1.5};  // and one of one thread, ended before the deadline
  EXPECT_DOUBLE_EQ(waited_for_a_core(waits), 3.0 + 1.5);
  EXPECT_DOUBLE_EQ(waited_for_a_core({}), 0.0);
}

// The audit's submission: 50 threads that wake together every 0.5 s for 0.5 ms of work each (so a
// queue for the cores each time), SIGXCPU ignored. Its 0.4 s of CPU in 9 s summed 24.4 s of waits
// over its threads, and the grader called it starved by a busy machine: exit 1, the grader's
// failure, every grading of it again the same, where it is the student's time-out.
TEST(Grade, ThreadsThatQueueForTheCoresTogetherAreTheCodesOwnTimeOut) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path submission = solution_with_euler_step_starting(
      dir, "queues", "look_starved();",
      "#include <chrono>\n#include <condition_variable>\n#include <csignal>\n#include <mutex>\n#include <thread>\n"
      "namespace {\n"
      "void look_starved() {\n"
      "  std::signal(SIGXCPU, SIG_IGN);\n"
      "  static std::mutex m; static std::condition_variable cv; static long generation = 0;\n"
      "  for (int i = 0; i < 50; ++i)\n"
      "    std::thread([] {\n"
      "      long seen = 0;\n"
      "      for (;;) {\n"
      "        { std::unique_lock<std::mutex> l(m); cv.wait(l, [&] { return generation != seen; }); seen = generation; }\n"
      "        const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(500);\n"
      "        while (std::chrono::steady_clock::now() < until) {}\n"
      "      }\n"
      "    }).detach();\n"
      "  for (;;) {\n"
      "    std::this_thread::sleep_for(std::chrono::milliseconds(500));\n"
      "    { std::lock_guard<std::mutex> l(m); ++generation; }\n"
      "    cv.notify_all();\n"
      "  }\n"
      "}\n"
      "}  // namespace\n");
  ASSERT_FALSE(submission.empty());
  const json result = graded_on_the_euler_table(dir, submission);
  EXPECT_EQ(failed(result), std::set<std::string>{"euler.table"}) << result.dump(2);
  EXPECT_NE(result.dump().find("timed out after 7 s waiting, not computing"), std::string::npos) << result.dump(2);
}

// Code that says what bubblewrap says when it cannot start the server ("bwrap: …", exit 1) as it
// loads: it made its grading the grader's failure (exit 1, no score), every grading of it again
// the same. The server says it serves before it loads the student's code; after that, an exit is
// the code's, whatever it printed.
TEST(Grade, CodeThatPretendsToBeBubblewrapFailingIsTheStudentsFailure) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path submission = solution_with_euler_step_starting(
      dir, "pretends", "",
      "#include <unistd.h>\n"
      "namespace { struct Pretend { Pretend() { static const char m[] = \"bwrap: execvp /motus/motus: Permission denied\\n\";"
      " (void)!::write(2, m, sizeof m - 1); ::_exit(1); } } pretend; }\n");
  ASSERT_FALSE(submission.empty());
  const json result = graded_on_the_euler_table(dir, submission);
  EXPECT_EQ(failed(result), std::set<std::string>{"euler.table"}) << result.dump(2);
  EXPECT_NE(result.dump().find("exited with status 1"), std::string::npos) << result.dump(2);
}

// The compiler's messages begin with a file's name, which #line sets: code whose error looked like
// bubblewrap failing to start the compiler made its grading the grader's failure (exit 1, no
// score), every time. It does not compile: the student's 0, with the compiler's words.
TEST(Grade, ACompileErrorThatPretendsToBeBubblewrapFailingIsTheStudentsFailure) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path submission = solution_with_euler_step_starting(
      dir, "pretends", "", "#line 1 \"bwrap: execvp /usr/bin/g++: Permission denied\"\n#error pretending\n");
  ASSERT_FALSE(submission.empty());
  const json result = graded_on_the_euler_table(dir, submission);
  EXPECT_EQ(result.value("score", -1.0), 0) << result.dump(2);
  EXPECT_NE(result.dump().find("does not compile"), std::string::npos) << result.dump(2);
  EXPECT_NE(result.dump().find("#error pretending"), std::string::npos) << result.dump(2);
}

// bubblewrap that cannot start the test's server (the audit's "bwrap: execvp /motus/motus:
// Permission denied", while motus was being relinked) read as the student's code exiting with
// status 1, every test lost. It is the grader's failure: exit 1, and a results file that says so.
TEST(Grade, BubblewrapFailingToStartTheServerIsTheGradersFailure) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path bwrap = dir / "bwrap";
  write_file(bwrap,
             "#!/bin/sh\n"
             "for a in \"$@\"; do if [ \"$a\" = serve ]; then echo 'bwrap: execvp /motus/motus: Permission denied' >&2; exit 1; fi; done\n"
             "exec /usr/bin/bwrap \"$@\"\n");
  fs::permissions(bwrap, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                             fs::perms::others_exec);
  const fs::path assignment = integrators_with_tests(dir, "one", json::array({definitions("integrators").at("euler.table")}));
  const fs::path submission = copy_solution(dir, "integrators", "solution");
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()},
                           {"MOTUS_BWRAP=" + bwrap.string()});
  EXPECT_EQ(r.status, 1) << r.err << r.out;
  EXPECT_NE(r.err.find("the sandbox could not start the student's code's server: bwrap: execvp /motus/motus: Permission denied"),
            std::string::npos)
      << r.err;
  const json result = read_json(dir / "results.json");
  EXPECT_EQ(result["extra_data"]["internal_error"], true) << result.dump(2);
  EXPECT_NE(result["output"].get<std::string>().find("This is a fault of the grader, not of the submission"), std::string::npos)
      << result.dump(2);
}

// A compiler stopped by the grader's own file-size limit (`ulimit -f 64`, which the sandbox cannot raise to
// the 64 MB a build may write without CAP_SYS_RESOURCE) graded the course's solution "does not compile", 0
// points, exit 0. It is the machine's limit: the grader's failure, exit 1, a results file that says so.
// (Where the sandbox can raise the limit, the build runs under its own and the solution compiles.)
TEST(Grade, ACompilerStoppedByTheGradersOwnFileSizeLimitIsTheGradersFailure) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path assignment = integrators_with_tests(dir, "one", json::array({definitions("integrators").at("euler.table")}));
  const fs::path submission = copy_solution(dir, "integrators", "solution");
  const auto r = run_program(dir, "/usr/bin/prlimit",
                             {"--fsize=65536", "--", kMotus, "grade", assignment.string(), submission.string(), "--results",
                              (dir / "results.json").string()});
  const json result = read_json(dir / "results.json");
  if (r.status == 0) {  // (the sandbox raised the limit)
    EXPECT_EQ(result["extra_data"]["compiled"], true) << result.dump(2);
    return;
  }
  EXPECT_EQ(r.status, 1) << r.err << r.out;
  EXPECT_NE(r.err.find("the compiler was stopped by this machine's file-size limit (ulimit -f: 64 KiB, below the 64 MB a "
                       "build may write): not the submission's fault"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(result["extra_data"]["internal_error"], true) << result.dump(2);
}

// A full disk: a tmpfs of 4 kB (one page) at DIR/small, mounted while it lives (not where the machine
// forbids it: then `mounted` is false).
struct SmallDisk {
  const TempDir& dir;
  fs::path at;
  bool mounted = false;
  explicit SmallDisk(const TempDir& d) : dir(d), at(d / "small") {
    fs::create_directories(at);
    mounted = run_program(dir, "/usr/bin/mount", {"-t", "tmpfs", "-o", "size=4k", "tmpfs", at.string()}).status == 0;
  }
  ~SmallDisk() {
    if (mounted) run_program(dir, "/usr/bin/umount", {at.string()});
  }
};

// A batch on a disk that fills up: alice's results were written, bob's and the scores.csv were not, and
// the message said "the 2 submissions' results are kept", with no word of bob. It names what is kept
// and what is not, and says the grader failed on bob. (An audit of failed writes: a tmpfs of 12 kB; here of 4.)
TEST(Grade, ABatchOnAFullDiskNamesTheResultsItCouldNotWrite) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path assignment = integrators_with_tests(dir, "one", json::array({definitions("integrators").at("euler.table")}));
  copy_solution(dir, "integrators", "batch/alice");
  copy_solution(dir, "integrators", "batch/bob");
  const SmallDisk disk(dir);
  if (!disk.mounted) GTEST_SKIP() << "no tmpfs can be mounted here";
  const fs::path small = disk.at;
  const auto r = run_motus(dir, {"grade", assignment.string(), "--batch", (dir / "batch").string(), "--out",
                                 (small / "graded").string()});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("motus: the grader failed on bob: " + (small / "graded").string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("scores.csv: could not be written (No space left on device); the results of 1 of the 2 "
                       "submissions are kept in " + (small / "graded").string() + "/ (no scores.csv); none could be "
                       "written for bob\n"),
            std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(small / "graded" / "alice.json"));
  EXPECT_FALSE(fs::exists(small / "graded" / "bob.json"));
}

// --plugin-out on a full disk said "--plugin-out: the plug-in could not be written (Input/output error)":
// libstdc++'s copy_file reports a short copy as EIO. It names the file and the cause. (An audit of failed
// writes: a tmpfs of 8 kB; here of 4.)
TEST(Grade, PluginOutOnAFullDiskNamesTheFileAndTheCause) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path assignment = integrators_with_tests(dir, "one", json::array({definitions("integrators").at("euler.table")}));
  const fs::path submission = copy_solution(dir, "integrators", "solution");
  const SmallDisk disk(dir);
  if (!disk.mounted) GTEST_SKIP() << "no tmpfs can be mounted here";
  const fs::path small = disk.at;
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string(),
                                 "--plugin-out", (small / "plugin.so").string()});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find((small / "plugin.so").string() + ": could not be written (No space left on device)"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(small / "plugin.so"));
}

// bubblewrap that cannot start the compiler (it says so and exits 1, for the compile and for the
// look at the compiler's version that then tells it from a compile error that says the same): the
// grader's failure, exit 1, and a results file that says so.
TEST(Grade, BubblewrapFailingToStartTheCompilerIsTheGradersFailure) {
  NEEDS_SANDBOX();
  TempDir dir;
  const fs::path bwrap = dir / "bwrap";
  write_file(bwrap,
             "#!/bin/sh\n"
             "for a in \"$@\"; do if [ \"$a\" = /usr/bin/g++ ]; then echo 'bwrap: execvp /usr/bin/g++: Permission denied' >&2; exit 1; fi; done\n"
             "exec /usr/bin/bwrap \"$@\"\n");
  fs::permissions(bwrap, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                             fs::perms::others_exec);
  const fs::path assignment = integrators_with_tests(dir, "one", json::array({definitions("integrators").at("euler.table")}));
  const fs::path submission = copy_solution(dir, "integrators", "solution");
  const auto r = run_motus(dir, {"grade", assignment.string(), submission.string(), "--results", (dir / "results.json").string()},
                           {"MOTUS_BWRAP=" + bwrap.string()});
  EXPECT_EQ(r.status, 1) << r.err << r.out;
  EXPECT_NE(r.err.find("the sandbox could not start the compiler: bwrap: execvp /usr/bin/g++: Permission denied"), std::string::npos)
      << r.err;
  const json result = read_json(dir / "results.json");
  EXPECT_EQ(result["extra_data"]["internal_error"], true) << result.dump(2);
}

// --jobs above the cores is allowed, with one line that says the tests will wait for a core.
TEST(Grade, MoreJobsThanCoresIsOneWarning) {
  NEEDS_SANDBOX();
  const long cores = [] {
    cpu_set_t set;
    CPU_ZERO(&set);
    return ::sched_getaffinity(0, sizeof set, &set) == 0 ? static_cast<long>(CPU_COUNT(&set)) : ::sysconf(_SC_NPROCESSORS_ONLN);
  }();
  if (cores >= 64) GTEST_SKIP() << "--jobs goes to 64";
  TempDir dir;
  fs::create_directories(dir / "batch/empty");  // (nothing to build: quick)
  auto r = run_motus(dir, {"grade", "integrators", "--batch", (dir / "batch").string(), "--jobs", std::to_string(cores + 1),
                           "--out", (dir / "many").string()});
  EXPECT_EQ(r.status, 0) << r.err;
  const std::string warning = "motus: warning: --jobs " + std::to_string(cores + 1) + " is more than this machine's " +
                              std::to_string(cores) + " core" + (cores == 1 ? "" : "s") +
                              ": tests will wait for a core, and take longer\n";
  EXPECT_EQ(r.err.rfind(warning, 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("warning", warning.size()), std::string::npos) << r.err;  // once
  r = run_motus(dir, {"grade", "integrators", "--batch", (dir / "batch").string(), "--jobs", std::to_string(cores), "--out",
                      (dir / "as-many").string()});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
}

// Hidden tests under /usr (bound read-only into every sandbox) would be readable by the student's
// code: refused before anything is graded, however the folder is reached (here through a link).
TEST(Grade, HiddenTestsWhereTheSandboxShowsThemAreRefused) {
  TempDir dir;
  const std::string solution = (fs::path(kAssignments) / "integrators/solution").string();
  fs::create_directory_symlink("/usr/share", dir / "looks-elsewhere");
  for (const std::string& hidden_folder : {std::string("/usr/share"), (dir / "looks-elsewhere").string()}) {
    const auto r = run_motus(dir, {"grade", "integrators", solution, "--hidden", hidden_folder, "--results",
                                   (dir / "results.json").string(), "--overwrite"});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(r.err, "motus: error: " + hidden_folder +
                         ": --hidden: is under /usr, which the sandbox shows the student's code (read-only): it could read "
                         "the hidden tests; keep them elsewhere, readable by the grader only\n");
    EXPECT_EQ(r.out, "");
  }
  // The folder of the assignment's own hidden tests is not under one: an empty submission is graded.
  if (!sandbox_available()) return;
  fs::create_directories(dir / "empty");
  const auto r = run_motus(dir, {"grade", "integrators", (dir / "empty").string(), "--hidden", hidden("integrators")});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("--hidden"), std::string::npos) << r.err;
}

}  // namespace

namespace {

// An ASSIGNMENT spelt with a trailing slash (shell completion adds one) named nothing: the batch's
// folder was runs/grade-scene-…, not runs/grade-integrators-…; and a submission folder with a legal
// name of 240 bytes failed after its grading ("File name too long": its results file's temporary
// .NAME.json.partial-XXXXXX was longer than a name may be), 0 points, "grader failed", exit 1.
TEST(Grade, AnAssignmentWithATrailingSlashAndALongSubmissionNameAreGradedAsNamed) {
  NEEDS_SANDBOX();
  TempDir dir;
  const std::string long_name(240, 'n');
  copy_solution(dir, "integrators", "batch/" + long_name);
  // (in dir, for its runs/: env -C, no shell)
  const auto r = run_program(dir, "/usr/bin/env", {"-C", dir.path().string(), kMotus, "grade",
                                                   (fs::path(kAssignments) / "integrators").string() + "/", "--batch",
                                                   (dir / "batch").string()});
  ASSERT_EQ(r.status, 0) << r.err;
  std::string folder;
  for (const auto& e : fs::directory_iterator(dir / "runs")) folder = e.path().filename().string();
  EXPECT_EQ(folder.rfind("grade-integrators-", 0), 0u) << folder;
  // The reference solution, whole marks: its results file there, and its row score = max_score.
  const json result = read_json(dir / "runs" / folder / (long_name + ".json"));
  double max_score = 0;
  for (const auto& t : result["tests"]) max_score += t["max_score"].get<double>();
  EXPECT_GT(max_score, 0);
  EXPECT_EQ(result["score"].get<double>(), max_score);
  std::ostringstream row;
  row << long_name << "," << max_score << "," << max_score << ",";
  EXPECT_NE(read_file(dir / "runs" / folder / "scores.csv").find(row.str()), std::string::npos)
      << read_file(dir / "runs" / folder / "scores.csv");
}

// Found by an audit of `motus grade` on a terminal: after the first test the bar said 100 % with 2
// of 31 tests done, alternating with the test's name, and nothing was shown in the 9–11 s of the
// compile. The build is named while it runs, and each test's bar is the share of the tests done
// before it (none says 100 %: the last test is not done when it starts).
TEST(Grade, ItsProgressNamesTheBuildAndCountsTheTestsDone) {
  TempDir dir;
  const auto r = run_motus(dir, {"grade", "integrators", (fs::path(kAssignments) / "integrators/solution").string(),
                                 "--hidden", hidden("integrators"), "--no-sandbox"},
                           {"MOTUS_PROGRESS=always", "COLUMNS=200"});
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> order;  // the rubric's tests, in the order they run
  const json rubric = read_json(fs::path(kAssignments) / "integrators/rubric.json");  // (named: see definitions())
  for (const auto& t : rubric["tests"]) order.push_back(t["name"].get<std::string>());
  const std::regex testing(R"(^grade integrators, testing (\S+) \[[#.]+\] +(\d+)%)");
  std::vector<std::string> lines;  // what each redraw showed
  std::stringstream drawn(r.err);
  for (std::string line; std::getline(drawn, line, '\r');)
    if (line.find_first_not_of(' ') != std::string::npos) lines.push_back(line);
  size_t compiling = lines.size(), tests = 0;
  for (size_t k = 0; k < lines.size(); ++k) {
    if (compiling == lines.size() && lines[k].rfind("grade integrators, compiling the submission  ", 0) == 0) compiling = k;
    std::smatch m;
    if (!std::regex_search(lines[k], m, testing)) continue;
    ++tests;
    const auto at = std::find(order.begin(), order.end(), m[1].str());
    ASSERT_NE(at, order.end()) << lines[k];
    EXPECT_NEAR(std::stod(m[2].str()), 100.0 * static_cast<double>(at - order.begin()) / static_cast<double>(order.size()),
                0.51)
        << lines[k];
    EXPECT_GT(k, compiling) << "a test before the build: " << lines[k];
  }
  EXPECT_LT(compiling, lines.size()) << "the build was not named:\n" << r.err;
  EXPECT_GE(tests, 1u) << r.err;
  EXPECT_EQ(r.err.find("100%"), std::string::npos) << r.err;
}

// Found by an audit: with a relative entry in PATH (PATH=relbin:/usr/bin:/bin, relbin/zip a link to
// zip) the package failed, "zip failed to write it (exit status -1)": zip was found as relbin/zip
// and started in the folder it zips. A program found on PATH is an absolute path.
TEST(Grade, APackageIsZippedWithAZipFoundThroughARelativePathEntry) {
  if (!fs::exists("/usr/bin/zip")) GTEST_SKIP() << "no /usr/bin/zip";
  TempDir dir;
  fs::create_directories(dir / "relbin");
  fs::create_symlink("/usr/bin/zip", dir / "relbin/zip");
  const auto r = run_program(dir, "/usr/bin/env",
                             {"-C", dir.path().string(), "PATH=relbin:/usr/bin:/bin", kMotus, "grade", "integrators",
                              "--package", "gradescope", "--out", "a.zip"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto listed = run_program(dir, "/usr/bin/unzip", {"-l", (dir / "a.zip").string()});
  EXPECT_NE(listed.out.find("run_autograder"), std::string::npos) << listed.out << listed.err;
}

}  // namespace

// TMPDIR set but empty is TMPDIR unset, as mktemp and POSIX's tools take it: `TMPDIR= motus grade …`
// failed with "TMPDIR=: cannot make a temporary folder there" (found by an audit of the surroundings
// motus runs in).
TEST(Grade, AnEmptyTmpdirIsTheSystemsTemporaryFolder) {
  const char* before = std::getenv("TMPDIR");
  const std::string kept = before ? before : "";
  ::setenv("TMPDIR", "", 1);
  std::string folder;
  EXPECT_NO_THROW(folder = motus::grade::make_temporary_folder("", "motus-empty-tmpdir-"));
  if (before) ::setenv("TMPDIR", kept.c_str(), 1);
  else ::unsetenv("TMPDIR");
  EXPECT_EQ(fs::path(folder).parent_path(), fs::path("/tmp"));
  EXPECT_TRUE(fs::is_directory(folder));
  if (!folder.empty()) fs::remove(folder);
}

// ---------------------------------------------------------------------------------------------------
// A student's walkthrough (an audit): compare's advice, a plug-in that does nothing, the wrong plug-in,
// the list of integrators, and a grader's velocities.

namespace {

// compare kepler with the student's symplectic Euler ended "motus integrated with symplectic-euler
// (student:symplectic-euler in student), Box2D and Bullet with symplectic Euler (their own): part of
// any difference is the method's" — the same method, all four 0.058 m from the orbit: the annotated
// integrator was compared with "symplectic-euler". The position-first symplectic-euler-x is another
// method than the peers' (velocity first), and the sentence says which is which.
TEST(Plugins, CompareCallsTheStudentsSymplecticEulerThePeersMethod) {
  TempDir dir;
  const std::string plugin = kAssignmentPlugins + "/integrators-solution.so";
  auto notice = [&](const std::string& integrator) {
    const auto r = run_motus(dir, {"compare", "kepler", "--plugin", plugin, "--integrator", integrator, "--engines",
                                   "motus,student,box2d", "--repeats", "1", "--json", "--out",
                                   (dir / integrator.substr(integrator.find(':') + 1)).string()});
    EXPECT_EQ(r.status, 0) << r.err;
    const json summary = json::parse(r.out, nullptr, false);
    return summary.is_object() && summary.contains("notice") ? summary["notice"].get<std::string>() : std::string();
  };
  const std::string same = notice("student:symplectic-euler");
  EXPECT_NE(same.find("Kepler's orbit"), std::string::npos) << same;
  EXPECT_EQ(same.find("motus integrated with"), std::string::npos) << same;
  EXPECT_EQ(same.find("like with like"), std::string::npos) << same;
  const std::string other = notice("student:symplectic-euler-x");
  EXPECT_NE(other.find("motus integrated with symplectic-euler-x (student:symplectic-euler-x in student), symplectic "
                       "Euler position first (x += v h, then v += a h), Box2D and Bullet with symplectic Euler velocity "
                       "first (v += a h, then x += v h; their own)"),
            std::string::npos)
      << other;
  EXPECT_NE(other.find("--integrator symplectic-euler compares like with like."), std::string::npos) << other;
}

// `run spring --plugin cloth.so` and `run kepler --plugin collisions.so` said nothing of the plug-in
// having no part in the run. One note on standard error says so (standard output stays the JSON's),
// in run and in compare; a plug-in that is used has none.
TEST(Plugins, APluginOfWhichTheRunUsesNothingSaysSoOnStandardError) {
  TempDir dir;
  const std::string cloth = kAssignmentPlugins + "/cloth-solution.so";
  const std::string collisions = kAssignmentPlugins + "/collisions-solution.so";
  const std::string integrators = kAssignmentPlugins + "/integrators-solution.so";
  struct Case {
    std::vector<std::string> args;
    std::string note;  // "": none
  };
  const std::vector<Case> cases = {
      {{"run", "spring", "--plugin", cloth, "--json"},
       "note: the plug-in " + cloth + " brings a constraint projection, and spring has no sticks or pins: it is not used in this run\n"},
      {{"run", "kepler", "--plugin", collisions, "--json"},
       "note: the plug-in " + collisions + " brings collision rules, and kepler has no collisions: it is not used in this run\n"},
      {{"run", "kepler", "--plugin", integrators, "--json"},
       "note: the plug-in " + integrators + " brings 8 integrators (student:euler, student:midpoint, …), and this run "
       "integrates with velocity-verlet (--integrator student:NAME runs one of them): it is not used in this run\n"},
      {{"run", "lorenz", "--plugin", cloth, "--json"},
       "note: the plug-in " + cloth + " brings a constraint projection, and lorenz is a first-order system, with no "
       "bodies: it is not used in this run\n"},
      {{"compare", "kepler", "--plugin", collisions, "--json", "--out", (dir / "kepler").string()},
       "note: the plug-in " + collisions + " brings collision rules, and kepler has no collisions: it is not used in this run\n"},
      {{"compare", "kepler", "--plugin", collisions, "--engines", "motus,box2d", "--json", "--out", (dir / "left-out").string()},
       "note: the plug-in " + collisions + " brings collision rules, and --engines leaves out its column (student): it is "
       "not used in this run\n"},
      {{"run", "bouncing_balls", "--plugin", collisions, "--json"}, ""},
      {{"run", "cloth", "--plugin", cloth, "--json"}, ""},
      {{"run", "kepler", "--plugin", integrators, "--integrator", "student:symplectic-euler", "--json"}, ""},
      {{"compare", "newtons_cradle", "--plugin", collisions, "--json", "--out", (dir / "cradle").string()}, ""},
  };
  for (auto c : cases) {
    c.args.insert(c.args.end(), {"--repeats", "1"});
    const auto r = run_motus(dir, c.args);
    SCOPED_TRACE(c.args[1] + " " + c.args[3]);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_FALSE(json::parse(r.out, nullptr, false).is_discarded()) << r.out;  // (the note is not in it)
    if (c.note.empty()) {
      EXPECT_EQ(r.err.find("note: the plug-in"), std::string::npos) << r.err;
    } else {
      EXPECT_NE(r.err.find(c.note), std::string::npos) << r.err;
    }
  }
}

// `run spring --plugin collisions.so --integrator student:euler` said only `unknown integrator
// "student:euler"`: which plug-in brings student: integrators was for the student to guess.
TEST(Plugins, AStudentIntegratorNotInThePluginSaysWhatThePluginBrings) {
  TempDir dir;
  const std::string collisions = kAssignmentPlugins + "/collisions-solution.so";
  const std::string integrators = kAssignmentPlugins + "/integrators-solution.so";
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  const std::vector<Case> cases = {
      {{"run", "spring", "--plugin", collisions, "--integrator", "student:euler"},
       "unknown integrator \"student:euler\": the plug-in " + collisions +
           " brings no integrators (it brings collision rules); the integrators assignment's plug-in does\n"},
      {{"run", "spring", "--plugin", kAssignmentPlugins + "/cloth-solution.so", "--integrator", "student:euler"},
       "brings no integrators (it brings a constraint projection); the integrators assignment's plug-in does\n"},
      {{"compare", "spring", "--plugin", collisions, "--integrator", "student:euler", "--out", (dir / "c").string()},
       "brings no integrators (it brings collision rules)"},
      {{"run", "spring", "--integrator", "student:euler"},
       "; student:NAME integrators come from a plug-in, and none is loaded: load its plug-in with --plugin FILE.so\n"},
      {{"run", "spring", "--plugin", integrators, "--integrator", "student:rk45"},
       "unknown integrator \"student:rk45\", did you mean student:rk4? (" + integrators +
           " brings student:euler, student:midpoint, student:rk4, student:rk4-doubling, student:symplectic-euler, "
           "student:symplectic-euler-x, student:velocity-verlet, student:verlet); motus's own is --integrator rk45\n"},
      {{"run", "spring", "--plugin", collisions, "--integrator", "bad:euler"},
       "; no loaded plug-in is named \"bad\" (loaded: \"student\" from " + collisions + ")\n"},
  };
  for (const auto& c : cases) {
    const auto r = run_motus(dir, c.args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
}

// The integrators `motus list --plugin PLUGIN` lists: the built-ins and the plug-in's.
std::set<std::string> integrators_listed(TempDir& dir, const std::string& plugin) {
  const auto r = run_motus(dir, {"list", "--plugin", plugin});
  EXPECT_EQ(r.status, 0) << r.err;
  std::set<std::string> known;
  std::stringstream lines(r.out.substr(r.out.find("\nintegrators:\n") + 14));
  for (std::string line; std::getline(lines, line) && line.rfind("  ", 0) == 0;)
    known.insert(line.substr(2, line.find(' ', 2) - 2));
  return known;
}

// An error's "(known: a, b, …and N more)": every name whole and known, the count last, and together
// every known name.
void expect_whole_names(const std::string& err, const std::set<std::string>& known) {
  const size_t from = err.find("(known: ");
  ASSERT_NE(from, std::string::npos) << err;
  const std::string list = err.substr(from + 8, err.find(')', from) - from - 8);
  std::stringstream items(list);
  size_t listed = 0, more = 0;
  for (std::string item; std::getline(items, item, ',');) {
    if (item.front() == ' ') item.erase(0, 1);
    std::smatch m;
    if (std::regex_match(item, m, std::regex("…and ([0-9]+) more"))) {
      more = std::stoul(m[1]);
      continue;
    }
    EXPECT_EQ(more, 0u) << "a name after the count: " << err;
    EXPECT_TRUE(known.count(item)) << "\"" << item << "\" is no integrator's whole name: " << err;
    ++listed;
  }
  EXPECT_EQ(listed + more, known.size()) << err;
}

// The unknown integrator's list, with a plug-in's eight names, was longer than an error's line and
// was cut in its middle, inside a name: "symplectic-eule…verlet". The names are whole, and those
// that do not fit are counted: "…and 6 more". (Also behind a long name, which the line's cut takes.)
TEST(Plugins, TheListOfKnownIntegratorsHasOnlyWholeNames) {
  TempDir dir;
  const std::string integrators = kAssignmentPlugins + "/integrators-solution.so";
  const std::set<std::string> known = integrators_listed(dir, integrators);
  ASSERT_EQ(known.size(), 19u);
  for (const std::string& name : {std::string("studen:euler"), std::string("no-such-integrator"), std::string(300, 'x')}) {
    const auto r = run_motus(dir, {"run", "spring", "--plugin", integrators, "--integrator", name});
    SCOPED_TRACE(name);
    EXPECT_EQ(r.status, 2) << r.err;
    ASSERT_EQ(count_lines(r.err), 1) << r.err;
    expect_whole_names(r.err, known);
  }
}

}  // namespace

// Newton's cradle's velocities were 10 numbers in a row for 5 balls in 2-D, "(1, 0, 0, 0, 0, 0, 0, 0,
// 0, 0)": which ball had which was the student's to count out. They are said body by body, measured and
// expected alike.
TEST(Grade, FinalVelocitiesAreSaidBodyByBody) {
  NEEDS_SANDBOX();
  TempDir dir;
  const auto r = run_motus(dir, {"grade", "collisions", (fs::path(kAssignments) / "collisions/starter").string(),
                                 "--results", (dir / "results.json").string()});
  ASSERT_TRUE(fs::exists(dir / "results.json")) << r.err;
  const json result = read_json(dir / "results.json");
  const json* cradle = test_named(result, "scene.newtons-cradle");
  ASSERT_NE(cradle, nullptr) << result.dump(2);
  const std::string output = (*cradle)["output"];
  EXPECT_NE(output.find("Measured: velocities at t = 3: body 0 (1, 0), body 1 (0, 0), body 2 (0, 0), body 3 (0, 0), "
                        "body 4 (0, 0).\nExpected: body 0 (0, 0), body 1 (0, 0), body 2 (0, 0), body 3 (0, 0), body 4 "
                        "(1, 0) (to 1e-09)."),
            std::string::npos)
      << output;
}

namespace {

// `render spring --plugin cloth.so` and `bench precision spring --plugin collisions.so` said nothing of
// the plug-in having no part in them, as run and compare now do. bench precision takes only
// integrators from a plug-in: collision rules or a projection are never used there, and a plug-in's
// integrators only when --integrators names one (or is not given) that can run the scene. One note on standard error;
// standard output (the render's summary, the sweep's table) has none.
TEST(Plugins, RenderAndBenchPrecisionSayAPluginTheyDoNotUseOnStandardError) {
  TempDir dir;
  const std::string cloth = kAssignmentPlugins + "/cloth-solution.so";
  const std::string collisions = kAssignmentPlugins + "/collisions-solution.so";
  const std::string integrators = kAssignmentPlugins + "/integrators-solution.so";
  const std::vector<std::string> render = {"--duration", "0.1", "--size", "64x48"};
  const std::vector<std::string> sweep = {"--levels", "1", "--per-decade", "1", "--repeats", "1"};
  struct Case {
    std::vector<std::string> args;
    std::string note;  // "": none
  };
  const std::vector<Case> cases = {
      {{"render", "spring", "--plugin", cloth, "--out", (dir / "spring").string()},
       "note: the plug-in " + cloth + " brings a constraint projection, and spring has no sticks or pins: it is not used in this run\n"},
      {{"render", "lorenz", "--plugin", collisions, "--out", (dir / "lorenz").string()},
       "note: the plug-in " + collisions + " brings collision rules, and lorenz is a first-order system, with no bodies: "
       "it is not used in this run\n"},
      {{"render", "kepler", "--plugin", integrators, "--out", (dir / "kepler").string()},
       "note: the plug-in " + integrators + " brings 8 integrators (student:euler, student:midpoint, …), and this run "
       "integrates with velocity-verlet (--integrator student:NAME runs one of them): it is not used in this run\n"},
      {{"bench", "precision", "spring", "--plugin", collisions, "--integrators", "rk4", "--out", (dir / "p1").string()},
       "note: the plug-in " + collisions + " brings collision rules, and bench precision takes only integrators from a "
       "plug-in: it is not used in this run\n"},
      {{"bench", "precision", "spring", "--plugin", cloth, "--out", (dir / "p2").string()},
       "note: the plug-in " + cloth + " brings a constraint projection, and bench precision takes only integrators from "
       "a plug-in: it is not used in this run\n"},
      {{"bench", "precision", "spring", "--plugin", integrators, "--integrators", "rk4", "--out", (dir / "p3").string()},
       "note: the plug-in " + integrators + " brings 8 integrators (student:euler, student:midpoint, …), and "
       "--integrators names none of its integrators (without --integrators each is swept): it is not used in this run\n"},
      // (student:verlet steps bodies: lorenz has none, and its curve says so; the note had counted it as used)
      {{"bench", "precision", "lorenz", "--plugin", integrators, "--integrators", "rk4,student:verlet", "--out",
        (dir / "p6").string()},
       "note: the plug-in " + integrators + " brings 8 integrators (student:euler, student:midpoint, …), and none of "
       "its integrators chosen can run this scene (their curves say why): it is not used in this run\n"},
      {{"render", "cloth", "--plugin", cloth, "--out", (dir / "cloth").string()}, ""},
      {{"render", "kepler", "--plugin", integrators, "--integrator", "student:verlet", "--out", (dir / "k2").string()}, ""},
      {{"bench", "precision", "spring", "--plugin", integrators, "--integrators", "rk4,student:rk4", "--out",
        (dir / "p4").string()},
       ""},
      {{"bench", "precision", "spring", "--plugin", integrators, "--out", (dir / "p5").string()}, ""},
  };
  for (auto c : cases) {
    const bool renders = c.args[0] == "render";
    c.args.insert(c.args.end(), renders ? render.begin() : sweep.begin(), renders ? render.end() : sweep.end());
    const auto r = run_motus(dir, c.args);
    SCOPED_TRACE(c.args[0] + " " + c.args[renders ? 1 : 2] + " " + c.args[renders ? 3 : 4]);
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_EQ(r.out.find("note:"), std::string::npos) << r.out;  // (standard output stays clean)
    if (c.note.empty()) {
      EXPECT_EQ(r.err.find("note: the plug-in"), std::string::npos) << r.err;
    } else {
      EXPECT_NE(r.err.find(c.note), std::string::npos) << r.err;
      EXPECT_EQ(r.err.find("note: the plug-in"), r.err.rfind("note: the plug-in")) << "said more than once: " << r.err;
    }
  }
}

// bench precision's unknown integrator listed every known one, a plug-in's eight included: behind a
// long name the list passed main's line of 400 bytes and was cut inside a name
// ("xxx…verlet, velocity-verlet"), or lost its "(known: " altogether. The names are whole, and those
// that do not fit are counted, as method_for's list does (TheListOfKnownIntegratorsHasOnlyWholeNames).
TEST(Plugins, BenchPrecisionsListOfKnownIntegratorsHasOnlyWholeNames) {
  TempDir dir;
  const std::string integrators = kAssignmentPlugins + "/integrators-solution.so";
  const std::set<std::string> known = integrators_listed(dir, integrators);
  ASSERT_EQ(known.size(), 19u);
  for (const std::string& name : {std::string("studen:euler"), std::string(100, 'y'), std::string(300, 'x')}) {
    const auto r = run_motus(dir, {"bench", "precision", "spring", "--plugin", integrators, "--integrators", name,
                                   "--out", (dir / "never").string()});
    SCOPED_TRACE(name);
    EXPECT_EQ(r.status, 2) << r.err;
    ASSERT_EQ(count_lines(r.err), 1) << r.err;
    expect_whole_names(r.err, known);
  }
  EXPECT_FALSE(fs::exists(dir / "never"));
}

}  // namespace
