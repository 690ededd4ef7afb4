#pragma once
// Compiling a submission into a plug-in, in the sandbox: the files the student handed in,
// with the assignment's own (its header and plugin.cpp), against the student API headers
// only — nothing else of motus, and never the solution or the hidden tests.
#include <string>
#include <vector>

#include "motus/grade/assignment.hpp"
#include "motus/grade/sandbox.hpp"

namespace motus::grade {

// Where the headers a plug-in is compiled against are (motus/student, motus/plugin and
// motus/external): the source tree's folders, or an installed include folder for all three.
struct ApiHeaders {
  std::string student;   // …/motus/student
  std::string plugin;    // …/motus/plugin
  std::string external;  // …/motus/external
};

// Every folder of the host a sandbox shows the student's code (read-only): /usr (sandbox.cpp) and
// the student API headers the compiler reads. (Other mounts are single files, or the grading's own
// temporary folders.) Hidden tests kept under one of them would be readable by the code.
std::vector<std::string> folders_in_sight(const ApiHeaders& headers);

struct BuildResult {
  bool ok = false;
  std::string plugin;  // the built plug-in, on the host
  std::string output;  // the compiler's messages, cut to a readable length
  double seconds = 0;
};

// `staged` holds copies of the handed-in files; `out` is an empty folder the sandbox may write;
// `provided` the folder of the assignment's provided files (its own, or a copy the sandbox's user
// can reach). Throws GradingInterrupted when `stop` (SandboxSpec::stop) ends the compiler's run.
BuildResult build_plugin(const Assignment& assignment, const std::string& provided, const std::string& staged,
                         const std::string& out, const ApiHeaders& headers, bool isolate, uid_t uid,
                         const std::function<bool()>& stop = {});

// The first `lines` lines of `text` (and at most `bytes` bytes), with a line saying how much
// was left out.
std::string cut(const std::string& text, size_t lines, size_t bytes);

// What the build test shows of a compile that ended as `ending`: a line of the grader's first when
// the compile used up its CPU limit, and one when the linker found no definition of a function the
// handout's headers (`handout`: their text) declare (defined with other parameters, in Eigen's words
// there), then "The compiler said:" and its messages (`errors`) cut, and how it ended.
std::string compiler_messages(const std::string& errors, const Ending& ending, const Limits& limits, double wall_seconds,
                              const std::string& handout = "");

}  // namespace motus::grade
