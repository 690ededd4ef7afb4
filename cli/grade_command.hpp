#pragma once
// `motus grade ASSIGNMENT SUBMISSION_DIR`: grade a student's submission of an assignment
// (assignments/) in a sandbox, into Gradescope's results.json and a readable summary.
//   --batch DIR [--jobs N]          every subfolder of DIR, one submission each; a CSV of scores
//   --package gradescope --out ZIP  the autograder zip for Gradescope
// See docs/grading.md.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

namespace motus::cli {

struct GradeCommandOptions {
  std::string assignment, submission;
  std::string results;            // --results FILE
  std::optional<std::string> format;  // what standard output shows: text (not given) or gradescope
  std::optional<std::string> hidden;
  double time_limit = 10;         // s per test
  long memory_limit = 512;        // MB
  bool no_sandbox = false;
  std::string plugin_out;         // keep the built plug-in here
  bool overwrite = false;
  std::string batch;              // --batch DIR
  std::optional<int> jobs;        // --batch: submissions at once (not given: 1)
  std::string out;                // --batch: the results folder; --package: the zip
  std::string package;            // "gradescope"
};

CLI::App* add_grade_command(CLI::App& app, GradeCommandOptions& options);
int grade_command(const GradeCommandOptions& options);

}  // namespace motus::cli
