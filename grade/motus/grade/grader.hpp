#pragma once
// Grading one submission: take the files the handout names, build them into a plug-in in a
// sandbox, run every test's check against the plug-in served from another sandbox, and
// write the result as Gradescope's results.json and as a readable summary.
#include <nlohmann/json.hpp>
#include <functional>
#include <string>
#include <vector>

#include "motus/grade/assignment.hpp"
#include "motus/grade/build.hpp"
#include "motus/grade/sandbox.hpp"

namespace motus::grade {

struct GradeOptions {
  std::string motus;      // this motus executable (the sandboxed server is `motus serve`)
  std::vector<std::string> modules;  // its modules a test may need, mounted beside it (ProbeSetup)
  // Asked while the grader waits for the student's code or its compiler: true (Ctrl-C) stops the
  // grading at once with GradingInterrupted (sandbox.hpp).
  std::function<bool()> stop;
  ApiHeaders headers;
  Limits limits;          // per test: its CPU; its wall clock is a backstop, wall_backstop(cpu_seconds)
  bool isolate = true;    // false: --no-sandbox
  std::string plugin_out; // also keep the built plug-in here ("" : no)
  std::string work_root;  // where the temporary folders go ("": the system's temporary folder)
  // Called as each test of the rubric starts (`done` of `total` finished): a test that runs to
  // its limit takes seconds, and a grading that says nothing for minutes looks stuck.
  std::function<void(size_t done, size_t total, const std::string& test)> progress;
  // Called as the build of the submission starts (not when a handed-in file is missing): the
  // compiler takes seconds (9–11 s for integrators) before any test starts.
  std::function<void()> building;
};

struct TestResult {
  std::string name, number, title;
  double score = 0, max_score = 0;
  bool passed = false;
  std::string output, visibility = "visible";
  // What the student's code printed during the test (Probe::printed), put below its output if it
  // fails; not in results.json otherwise.
  std::string printed;
};

struct GradeResult {
  std::string assignment, submission;
  std::vector<TestResult> tests;
  double score = 0, max_score = 0, seconds = 0;
  bool compiled = false;
  std::string output;  // the overall message, shown to students at once: of the tests they see now only
  std::string totals;  // every test's points and passes, for the instructor (text_summary), when some are not shown
};

GradeResult grade_submission(const Assignment& assignment, const std::string& submission, const GradeOptions& options);

// Gradescope's results.json (gradescope-autograders.readthedocs.io, "specs").
nlohmann::json gradescope_json(const GradeResult& result);
// The same as a person reads it.
std::string text_summary(const GradeResult& result);
// Whether a file's name is an archive's (integrators.zip, hw.tar.gz, in any case): a submission
// handed in packed, which is unpacked first.
bool looks_packed(const std::string& file_name);
// What a student wrote (their code's output, a folder name), made safe for a terminal: control
// characters but the line break and the tab become '?', as do C1 controls.
std::string terminal_safe(const std::string& text);

// A new folder `prefix`XXXXXX in `root` ("": the system's temporary folder, TMPDIR's), mode 0700.
// Throws std::runtime_error naming the folder (and TMPDIR) and why not.
std::string make_temporary_folder(const std::string& root, const std::string& prefix);
// The results.json of a grading that could not finish (an internal failure): valid, and says so.
nlohmann::json failed_json(const std::string& assignment, const std::string& why);
// A results.json's text. What the student's code and compiler said may be in any encoding (an
// editor that saves Latin-1): bytes that are not UTF-8 become U+FFFD instead of failing the write.
std::string results_text(const nlohmann::json& results);

}  // namespace motus::grade
