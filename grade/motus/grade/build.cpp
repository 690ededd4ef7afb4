#include "motus/grade/build.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <sys/resource.h>

namespace fs = std::filesystem;

namespace motus::grade {

std::string cut(const std::string& text, size_t lines, size_t bytes) {
  size_t end = 0, count = 0;
  while (end < text.size() && count < lines && end < bytes) {
    const size_t next = text.find('\n', end);
    end = next == std::string::npos ? text.size() : next + 1;
    ++count;
  }
  end = std::min(end, bytes);
  if (end >= text.size()) return text;
  size_t left = 0;
  for (size_t i = end; i < text.size(); ++i) left += text[i] == '\n';
  return text.substr(0, end) + "… (" + std::to_string(left) + " more lines left out)\n";
}

namespace {

// Whether the driver reported a process of its own killed by the CPU limit (RLIMIT_CPU's SIGXCPU):
// "g++: internal compiler error: CPU time limit exceeded signal terminated program cc1plus", on a
// line of its own that begins with the program's name (no path, no space: the student's words only
// come in lines that begin with a file's path or with spaces), and the internal compiler error's
// exit status, 4 (a student's #error with the same words exits with 1).
// (`signal`: the limit's words, as strsignal gives them: the file-size limit's SIGXFSZ is "File size
// limit exceeded".)
bool driver_reports(const std::string& errors, const Ending& ending, const char* signal = "CPU time limit exceeded") {
  if (!ending.exited || ending.status != 4) return false;
  for (size_t start = 0; start < errors.size();) {
    const size_t end = std::min(errors.find('\n', start), errors.size());
    const std::string line = errors.substr(start, end - start);
    const size_t colon = line.find(": ");
    if (colon != std::string::npos && colon > 0 && line.find_first_of("/ \t") > colon &&
        line.find(signal) != std::string::npos)
      return true;
    start = end + 1;
  }
  return false;
}

// Whether `spec`'s sandbox (its mounts, user and limits) starts the compiler: g++ --version, ended
// by itself with status 0 within 30 s.
bool starts_the_compiler(SandboxSpec spec, const Limits& limits) {
  spec.argv = {"/usr/bin/g++", "--version"};
  SandboxProcess compiler(spec, limits);
  const Ending ending = compiler.finish(std::chrono::steady_clock::now() + std::chrono::seconds(30));
  return ending.exited && ending.status == 0;
}

// The handout's functions the linker found no definition of, in order, once each: from the linker's
// own lines (`plugin.cpp:(.text+0x25e): undefined reference to `student::rk4_step(…)'`: an object's
// section, never a line of the student's own words, which begin with a file's line number), which name
// the parameters in Eigen's words and not the handout's (VectorInOut is an Eigen::Ref<…>). Only a name
// the handout's headers (`handout`, their text) declare as a function: a helper of the student's own,
// declared and never defined, is another mistake.
std::vector<std::string> undefined_handout_functions(const std::string& errors, const std::string& handout) {
  static const std::string kMark = ": undefined reference to `student::";
  std::vector<std::string> names;
  for (size_t start = 0; start < errors.size();) {
    const size_t end = std::min(errors.find('\n', start), errors.size());
    const std::string line = errors.substr(start, end - start);
    start = end + 1;
    // (GNU ld may begin the line with its own path: "/usr/bin/ld: plugin.cpp:(.text+0x25e): …")
    const std::string own = line.rfind("/usr/bin/ld: ", 0) == 0 ? line.substr(13) : line;
    const size_t mark = own.find(kMark), section = own.find(":(.");
    if (mark == std::string::npos || section == std::string::npos || own.find(' ') < section || section + 3 > mark) continue;
    const size_t name_begin = mark + kMark.size(), paren = own.find('(', name_begin);
    if (paren == std::string::npos) continue;  // (a variable: `student::kTable')
    const std::string name = own.substr(name_begin, paren - name_begin);
    bool declared = false;
    for (size_t at = handout.find(name); at != std::string::npos && !declared; at = handout.find(name, at + 1)) {
      const bool starts = at == 0 || !(std::isalnum(static_cast<unsigned char>(handout[at - 1])) || handout[at - 1] == '_');
      const size_t after = handout.find_first_not_of(" \t", at + name.size());
      declared = starts && after != std::string::npos && handout[after] == '(';
    }
    if (declared && std::find(names.begin(), names.end(), "student::" + name) == names.end()) names.push_back("student::" + name);
  }
  return names;
}

}  // namespace

std::string compiler_messages(const std::string& errors, const Ending& ending, const Limits& limits, double wall_seconds,
                              const std::string& handout) {
  // Stopped by its CPU limit: said first, on a line of its own that no cut removes. The driver
  // reports its killed cc1plus as "internal compiler error ... Please submit a full bug report", and
  // that alone (past the 40 lines shown when a flood of errors came first) told a student to
  // report a bug in GCC, with no word of the grader's limit.
  const bool reported = driver_reports(errors, ending);
  const bool out_of_cpu = reported || (!ending.timed_out && ending.out_of_time(limits, wall_seconds)) ||
                          (ending.timed_out && ending.verdict == WallVerdict::used_its_cpu);
  std::string output;
  if (out_of_cpu)
    output = fmt::format("Compiling used up the {:g} s of CPU the grader gives a compile, and the grader stopped the "
                         "compiler: code that makes the compiler work that long (a heavy constexpr evaluation or template "
                         "instantiation) cannot be graded; make that work lighter.{}\n",
                         cpu_limit_seconds(limits.cpu_seconds),
                         reported ? " The compiler's \"internal compiler error\" (and its \"bug report\") is that stop, not "
                                    "a bug in GCC to report."
                                  : "");
  const std::vector<std::string> undefined = undefined_handout_functions(errors, handout);
  if (!undefined.empty()) {
    std::string names;
    for (const auto& name : undefined) names += (names.empty() ? "" : ", ") + name;
    const bool one = undefined.size() == 1;
    output += fmt::format(
        "The handout's header declares {}, and your files define {} with exactly {} parameters: a function of the same "
        "name with other parameter types (Vector where the header has VectorInOut, a const left out) is another "
        "function. Copy {} first line from the header. (The linker below names the handout's types in Eigen's words: "
        "VectorInOut is Eigen::Ref<Eigen::Matrix<double, -1, 1, ...>>, VectorIn the same Ref of a const Matrix, Vector "
        "Eigen::Matrix<double, -1, 1, ...>.)\n",
        names, one ? "no function of that name" : "none of them", one ? "its" : "their", one ? "its" : "each one's");
  }
  output += "The compiler said:\n" + cut(errors, 40, 6000);
  if (!ending.exited || ending.status != 0) output += "(the compiler " + ending.describe(limits, wall_seconds) + ")\n";
  return output;
}

std::vector<std::string> folders_in_sight(const ApiHeaders& headers) {
  return {"/usr", headers.student, headers.plugin, headers.external};
}

BuildResult build_plugin(const Assignment& a, const std::string& provided, const std::string& staged, const std::string& out,
                         const ApiHeaders& headers, bool isolate, uid_t uid, const std::function<bool()>& stop) {
  const auto began = std::chrono::steady_clock::now();
  SandboxSpec spec;
  spec.isolate = isolate;
  spec.uid = uid;
  // Inside: the headers at /motus/include, the assignment's files at /assignment, the
  // submission at /submission, and /out for the plug-in. Without the sandbox, the same
  // files where they are.
  const std::string include = isolate ? "/motus/include" : "";
  const std::string assignment_dir = isolate ? "/assignment" : provided;
  const std::string submission_dir = isolate ? "/submission" : staged;
  const std::string out_dir = isolate ? "/out" : out;
  // -z defs: a function the handout asks for that the submission does not define (misspelt, or
  // with other parameters) is a link error naming it, here, not a plug-in that fails every test.
  std::vector<std::string> argv = {"/usr/bin/g++", "-std=c++20", "-O2", "-shared", "-fPIC", "-Wl,-z,defs",
                                   "-fvisibility=hidden", "-fvisibility-inlines-hidden", "-fdiagnostics-color=never",
                                   "-I" + assignment_dir};
  if (isolate) {
    spec.mounts = {{headers.student, "/motus/include/motus/student", false},
                   {headers.plugin, "/motus/include/motus/plugin", false},
                   {headers.external, "/motus/include/motus/external", false},
                   {staged, "/submission", false},
                   {out, "/out", true}};
    for (const auto& f : a.provided) spec.mounts.push_back({(fs::path(provided) / f).string(), "/assignment/" + f, false});
    argv.push_back("-I" + include);
  } else {
    argv.push_back("-I" + fs::path(headers.student).parent_path().parent_path().string());
    argv.push_back("-I" + fs::path(headers.external).parent_path().parent_path().string());
  }
  argv.insert(argv.end(), {"-isystem", "/usr/include/eigen3"});
  argv.insert(argv.end(), a.flags.begin(), a.flags.end());
  for (const auto& f : a.files)
    if (fs::path(f).extension() == ".cpp" || fs::path(f).extension() == ".cc") argv.push_back(submission_dir + "/" + f);
  for (const auto& f : a.provided)
    if (fs::path(f).extension() == ".cpp" || fs::path(f).extension() == ".cc") argv.push_back(assignment_dir + "/" + f);
  argv.insert(argv.end(), {"-o", out_dir + "/student.so"});
  spec.argv = argv;
  spec.workdir = "/tmp";
  spec.stop = stop;

  Limits limits;
  limits.cpu_seconds = 60;
  limits.memory_mb = 2048;
  limits.file_mb = 64;
  limits.processes = 64;
  limits.tmpfs_mb = 256;
  BuildResult result;
  bool interrupted = false;
  {
    // (A sandbox that cannot be made is the grader's fault, never the student's: it throws on.)
    SandboxProcess compiler(spec, limits);
    const auto started = std::chrono::steady_clock::now();
    // The wall clock is a backstop (wall_backstop: 125 s for the 60 s of CPU): a compiler waiting
    // for a core on a busy machine (a --jobs above the cores) is not the submission's failure.
    const double backstop = wall_backstop(limits.cpu_seconds);
    Ending ending = compiler.finish(started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                  std::chrono::duration<double>(backstop)));
    interrupted = compiler.interrupted();
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (ending.timed_out && !interrupted) {
      ending.verdict = judge_wall_timeout(ending.use, cpu_limit_seconds(limits.cpu_seconds));
      if (*ending.verdict == WallVerdict::starved)
        throw MachineTooBusy(starved_message("the compiler", ending.use, cpu_limit_seconds(limits.cpu_seconds)));
      wall = backstop;  // (as the submission's result says it: the same on any machine)
    }
    // (The handout's headers, read for the names they declare when the linker found a student's function
    // missing: a link error names the function by them.)
    std::string handout;
    if (compiler.errors().find("undefined reference to `student::") != std::string::npos)
      for (const auto& file : a.provided)
        if (const auto extension = fs::path(file).extension(); extension == ".hpp" || extension == ".h") {
          std::ifstream in(fs::path(provided) / file, std::ios::binary);
          handout += std::string(std::istreambuf_iterator<char>(in), {}) + "\n";
        }
    result.output = compiler_messages(compiler.errors(), ending, limits, wall, handout);
    result.ok = ending.exited && ending.status == 0 && fs::is_regular_file(fs::path(out) / "student.so");
    // bubblewrap's own failure (it prints "bwrap: …" and exits 1) is the sandbox's, not the code's.
    // The compiler's words start with a file's name, which the code can choose (#line 1 "bwrap:
    // execvp /usr/bin/g++: Permission denied" and an #error made a grading the grader's failure,
    // every time): so the same sandbox is asked to start the compiler once more, for its version,
    // and only when that fails too is it the sandbox's.
    if (!result.ok && !interrupted && compiler.errors().rfind("bwrap: ", 0) == 0 && !starts_the_compiler(spec, limits))
      throw std::runtime_error("the sandbox could not start the compiler: " +
                               compiler.errors().substr(0, compiler.errors().find('\n')));
    // The compiler stopped by a file-size limit below the one a build is given: the grader's own
    // (`ulimit -f`), which the sandbox cannot raise without the privilege to, is this machine's
    // limit, not the submission's — under `ulimit -f 64` the course's solution graded "does not
    // compile", 0 points, exit 0 (an audit).
    rlimit own{};
    const rlim_t build_may_write = static_cast<rlim_t>(limits.file_mb) << 20;
    if (!result.ok && !interrupted && driver_reports(compiler.errors(), ending, "File size limit exceeded") &&
        ::getrlimit(RLIMIT_FSIZE, &own) == 0 && own.rlim_cur != RLIM_INFINITY && own.rlim_cur < build_may_write)
      throw std::runtime_error(fmt::format("the compiler was stopped by this machine's file-size limit (ulimit -f: {} KiB, "
                                           "below the {} MB a build may write): not the submission's fault; raise it "
                                           "and grade again",
                                           own.rlim_cur >> 10, limits.file_mb));
  }
  if (interrupted) throw GradingInterrupted();
  result.plugin = (fs::path(out) / "student.so").string();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  return result;
}

}  // namespace motus::grade
