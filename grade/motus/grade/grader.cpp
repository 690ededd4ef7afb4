#include "motus/grade/grader.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>

#include "motus/grade/copy_files.hpp"
#include "motus/grade/probe.hpp"

namespace fs = std::filesystem;

namespace motus::grade {
namespace {

// Where a file the handout names may be instead, as a student hands it in: under another case
// (Integrators.cpp), in a folder (integrators/integrators.cpp), or packed (integrators.zip). ""
// when none of these is there. (The top level and one level down; links are not followed.)
std::string where_it_might_be(const std::string& submission, const std::string& name) {
  auto lower = [](std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
  };
  std::error_code error;
  int looked = 0;
  for (fs::directory_iterator top(submission, error), end; !error && top != end && looked < 1000; top.increment(error), ++looked) {
    const std::string found = top->path().filename().string();
    const std::string lowered = lower(found);
    if (lowered == lower(name) && top->is_regular_file(error))
      return " (there is " + found + ": names are case-sensitive, rename it " + name + ")";
    if (looks_packed(found)) return " (there is " + found + ": hand in the files themselves, unpacked)";
  }
  // In a folder, up to three down (a zip unpacked as name/src/...: one down only was looked at),
  // no link followed, a thousand entries at most.
  error.clear();
  looked = 0;
  for (fs::recursive_directory_iterator it(submission, error), end; !error && it != end && looked < 1000;
       it.increment(error), ++looked) {
    if (it.depth() >= 2) it.disable_recursion_pending();
    if (it.depth() >= 1 && it->path().filename() == name && fs::is_regular_file(fs::symlink_status(it->path(), error)))
      return " (there is " + it->path().lexically_relative(submission).string() +
             ": put it at the top of the submission, not in a folder)";
  }
  return "";
}

constexpr std::uintmax_t kMaxFileBytes = 1 << 20;  // a handed-in file larger than 1 MB is not source code

// A handed-in file: its bytes, or why it is not taken ("missing", or a reason to show).
struct HandedIn {
  std::optional<std::string> text;
  std::string why;
};

// Reads `name` in the submission's folder (open as `folder`) through one descriptor that follows
// no link: a link swapped in for the file, or for the folder once it is open, is not followed
// (on a machine the student also uses, it could lead the grader to the solution).
HandedIn read_handed_in(int folder, const std::string& name) {
  const char* not_regular = "not a regular file (a folder or a link is not taken)";
  const int fd = ::openat(folder, name.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    const int e = errno;
    return {std::nullopt, e == ENOENT ? "missing" : e == ELOOP ? not_regular : std::string("cannot be read (") + std::strerror(e) + ")"};
  }
  HandedIn in;
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    in.why = not_regular;
  } else if (static_cast<std::uintmax_t>(st.st_size) > kMaxFileBytes) {
    in.why = "larger than 1 MB";
  } else {
    std::string bytes(kMaxFileBytes + 1, '\0');  // (one more: a file that grew past the limit shows)
    size_t got = 0;
    for (ssize_t n; got < bytes.size() && (n = ::read(fd, bytes.data() + got, bytes.size() - got)) != 0;) {
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        in.why = std::string("cannot be read (") + std::strerror(errno) + ")";
        break;
      }
      got += static_cast<size_t>(n);
    }
    if (in.why.empty() && got > kMaxFileBytes) in.why = "larger than 1 MB";
    if (in.why.empty()) bytes.resize(got), in.text = std::move(bytes);
  }
  ::close(fd);
  return in;
}

// A fresh folder of our own for one grading, removed when done.
class WorkFolder {
public:
  explicit WorkFolder(const std::string& root) {
    path_ = make_temporary_folder(root, "motus-grade-");
    ::chmod(path_.c_str(), 0711);  // the sandbox's user may enter, not list
  }
  ~WorkFolder() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

private:
  fs::path path_;
};

TestResult gate(const std::string& name, const std::string& number, const std::string& title) {
  TestResult t;
  t.name = name;
  t.number = number;
  t.title = title;
  return t;
}

// The most of a test's own text (what was measured and expected, or what happened) its output
// keeps; what the student's code printed comes after it, cut to its own 1,200 bytes. Every check
// prints what it measured, and a reply the student's code wrote over the server's once put 9 MB
// of it in one test's output.
constexpr size_t kTestTextBytes = 5000;

std::string bounded(std::string text, size_t bytes) {
  if (text.size() <= bytes) return text;
  size_t cut = bytes;
  while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0) == 0x80) --cut;  // (not inside a UTF-8 character)
  return text.substr(0, cut) + "… (cut: " + std::to_string(text.size()) + " bytes in all)";
}

// Whether the file system holding `folder` has less than 64 MB left for this user (or cannot be
// looked at): no compiler's objects are made there then.
bool disk_nearly_full(const std::filesystem::path& folder) {
  struct statvfs disk {};
  if (::statvfs(folder.c_str(), &disk) != 0) return true;
  return static_cast<double>(disk.f_bavail) * static_cast<double>(disk.f_frsize) < 64.0 * 1024 * 1024;
}

}  // namespace

std::string make_temporary_folder(const std::string& root, const std::string& prefix) {
  const char* tmpdir = root.empty() ? std::getenv("TMPDIR") : nullptr;  // (named when it chose the folder)
  fs::path folder = root;
  if (tmpdir && !*tmpdir) {  // set but empty: unset, as mktemp and POSIX's tools take it (it failed with "TMPDIR=: …")
    folder = "/tmp";
    tmpdir = nullptr;
  } else if (root.empty()) {
    std::error_code error;
    folder = fs::temp_directory_path(error);
    if (error)
      throw std::runtime_error((tmpdir ? "TMPDIR=" + std::string(tmpdir) : std::string("the temporary folder")) +
                               ": cannot make a temporary folder there (" + error.message() + ")");
  }
  std::string pattern = (folder / (prefix + "XXXXXX")).string();
  if (!::mkdtemp(pattern.data()))
    throw std::runtime_error((tmpdir ? "TMPDIR=" : "") + folder.string() + ": cannot make a temporary folder there (" +
                             std::strerror(errno) + ")");
  return pattern;
}

GradeResult grade_submission(const Assignment& a, const std::string& submission, const GradeOptions& o) {
  const auto began = std::chrono::steady_clock::now();
  // For the tests of what an internal failure leaves behind (a valid results.json that says so).
  if (const char* fail = std::getenv("MOTUS_GRADE_FAIL"); fail && *fail)
    throw std::runtime_error("failure injected by MOTUS_GRADE_FAIL");
  GradeResult result;
  result.assignment = a.name;
  result.submission = submission;
  result.max_score = a.max_score();
  const SandboxUser user;  // this grading's own, for its build and every test
  WorkFolder work(o.work_root);
  const fs::path staged = work.path() / "submission", out = work.path() / "out";
  fs::create_directories(staged);
  fs::create_directories(out);
  ::chmod(staged.c_str(), 0755);
  if (::geteuid() == 0) {
    if (::chown(out.c_str(), user.uid(), user.uid()) != 0) throw std::runtime_error("cannot hand the build folder to the sandbox's user");
  }
  ::chmod(out.c_str(), 0700);
  // As root the student's code runs as the sandbox's user, sandbox or not (--no-sandbox): what it
  // will read (and the sandbox mount) must be within its reach, or every student fails for the
  // grader's fault. What motus brings — its API headers, the assignment's provided files, motus
  // itself and its modules — is copied into this grading's own folder when that user cannot reach
  // it where it is: root's clone in /root (0700, as Debian makes it) failed every grading with
  // "/root (mode 0700): the sandbox's user cannot pass through it". Every path is then checked:
  // the build's, the servers', the modules.
  ApiHeaders headers = o.headers;
  std::string provided = a.folder, motus = o.motus;
  std::vector<std::string> modules = o.modules;
  if (::geteuid() == 0) {
    const fs::path inputs = work.path() / "motus";
    auto out_of_reach = [&](const std::vector<std::string>& hosts) {
      return std::any_of(hosts.begin(), hosts.end(), [&](const std::string& h) { return !h.empty() && !unreachable_for(user.uid(), h).empty(); });
    };
    auto copy_in = [&](const std::string& host, const fs::path& copy) -> std::string {
      if (host.empty()) return host;
      std::error_code error;
      fs::create_directories(copy.parent_path(), error);
      if (!error) fs::copy(host, copy, fs::copy_options::recursive, error);  // (links followed: a copy of what they lead to)
      if (error)
        throw std::runtime_error(
            host + ": a copy in " + work.path().string() + " for the sandbox's user (who cannot reach it, or a file of its group, "
            "where it is) could not be made (" + error.message() + ")" +
            (error == std::errc::no_space_on_device || disk_nearly_full(work.path())  // (libstdc++'s copy may say EIO)
                 ? ": the grading stopped for want of disk space on this machine, not the submission's fault; free some space (or set TMPDIR) and grade again"
                 : ""));
      for (fs::path p = copy.parent_path(); p != work.path(); p = p.parent_path()) ::chmod(p.c_str(), 0755);
      auto open_to_all = [](const fs::path& p) {  // readable by all; runnable by all if it was by its owner
        const bool runnable = fs::is_directory(p) || (fs::status(p).permissions() & fs::perms::owner_exec) != fs::perms::none;
        ::chmod(p.c_str(), runnable ? 0755 : 0644);
      };
      open_to_all(copy);
      if (fs::is_directory(copy))
        for (const auto& e : fs::recursive_directory_iterator(copy)) open_to_all(e.path());
      return copy.string();
    };
    // Each group is copied whole when any of it is out of reach: the build without the sandbox
    // includes the headers from one folder (INCLUDE/motus/NAME, two levels kept) and the provided
    // files from another, and finds in them only what was copied.
    if (out_of_reach({o.headers.student, o.headers.plugin, o.headers.external})) {
      headers.student = copy_in(o.headers.student, inputs / "api/motus/student");
      headers.plugin = copy_in(o.headers.plugin, inputs / "api/motus/plugin");
      headers.external = copy_in(o.headers.external, inputs / "engine-api/motus/external");
    }
    std::vector<std::string> provided_files;
    for (const auto& f : a.provided) provided_files.push_back((fs::path(a.folder) / f).string());
    if (out_of_reach(provided_files)) {
      provided = (inputs / "assignment").string();
      for (const auto& f : a.provided) copy_in((fs::path(a.folder) / f).string(), inputs / "assignment" / f);
    }
    std::vector<std::string> programs = modules;  // motus and its modules, mounted side by side
    programs.push_back(o.motus);
    if (out_of_reach(programs)) {
      motus = copy_in(o.motus, inputs / "bin" / fs::path(o.motus).filename());
      for (auto& m : modules) m = copy_in(m, inputs / "bin" / fs::path(m).filename());
    }
    std::vector<std::string> used = {staged.string(), out.string(), headers.student, headers.plugin, headers.external, motus};
    for (const auto& f : a.provided) used.push_back((fs::path(provided) / f).string());
    used.insert(used.end(), modules.begin(), modules.end());
    for (const auto& path : used)
      if (!path.empty())
        if (const std::string why = unreachable_for(user.uid(), path); !why.empty())
          throw std::runtime_error(why + ". motus grade runs the student's code as a user of its own: every folder it "
                                         "uses must be open to others on the way (chmod o+x), TMPDIR's too");
  }

  // 1. The files the handout names, and only those, as regular files of a sensible size.
  TestResult files = gate("files", "0.1", "The handed-in files: " + fmt::format("{}", fmt::join(a.files, ", ")));
  std::string missing;
  // (The folder as given, links and all, opened once: what is read is in it, whatever is renamed.)
  const int folder = ::open(submission.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  for (const auto& name : a.files) {
    const HandedIn in = folder >= 0 ? read_handed_in(folder, name) : HandedIn{std::nullopt, "missing"};
    if (!in.text) {
      missing += "  " + name + ": " + in.why + (in.why == "missing" ? where_it_might_be(submission, name) : "") + "\n";
      continue;
    }
    errno = 0;
    std::ofstream out(staged / name, std::ios::binary | std::ios::trunc);
    out << *in.text;
    out.close();
    if (!out) {
      const int why = errno;  // (what the failed open, write or close left)
      if (folder >= 0) ::close(folder);
      throw std::runtime_error((staged / name).string() + ": could not be written (" +
                               (why ? std::strerror(why) : "the stream failed") + ")");
    }
    ::chmod((staged / name).c_str(), 0644);
  }
  if (folder >= 0) ::close(folder);
  files.passed = missing.empty();
  files.output = files.passed ? "Every file the handout names is there."
                              : "Not graded: these files are missing or cannot be taken (the handout names them; "
                                "put them at the top of the submission):\n" + missing;
  result.tests.push_back(files);

  // 2. The build.
  TestResult build = gate("build", "0.2", "The submission compiles into a plug-in");
  BuildResult built;
  if (files.passed) {
    if (o.building) o.building();
    built = build_plugin(a, provided, staged.string(), out.string(), headers, o.isolate, user.uid(), o.stop);
    // A disk that filled up under the compiler is this machine's failure, not the submission's: it
    // was graded "does not compile", 0 points, exit 0 — on Gradescope, every student at once. (The
    // disk is looked at too: a submission's #error could print the same words.)
    for (const char* machine : {"No space left on device", "Disk quota exceeded"})
      if (!built.ok && built.output.find(machine) != std::string::npos && disk_nearly_full(out))
        throw std::runtime_error(std::string("the build of the submission stopped for want of disk space on this machine (the "
                                             "compiler said: ") + machine + ", in " + out.parent_path().string() +
                                 "): not the submission's fault; free some space (or set TMPDIR) and grade again");
    build.passed = built.ok;
    build.output = built.ok ? fmt::format("Compiled in {:.1f} s.", built.seconds)
                            : "Not graded: the submission does not compile.\n" + built.output;  // (build.hpp's compiler_messages)
  } else {
    build.output = "Not built: a handed-in file is missing or cannot be taken (see \"files\").";
  }
  result.tests.push_back(build);
  result.compiled = build.passed;

  // 3. Every test of the rubric, each against its own deadline and in a server of its own.
  Limits limits = o.limits;
  ProbeSetup setup{motus, built.plugin, modules, o.stop, limits, o.isolate, user.uid()};
  Probe probe(setup);
  int number = 0;
  for (const auto& t : a.tests) {
    if (o.progress) o.progress(static_cast<size_t>(number), a.tests.size(), t.name);
    TestResult r;
    r.name = t.name;
    r.number = std::to_string(++number);
    r.title = t.title;
    r.max_score = t.points;
    r.visibility = t.visibility;
    if (!build.passed) {
      r.output = files.passed ? "Not run: the submission does not compile (see \"build\")."
                              : "Not run: a handed-in file is missing or cannot be taken (see \"files\").";
    } else {
      // A server of its own: RLIMIT_CPU counts a process's whole life, so a server kept from
      // the tests before would leave this one only what they did not use (and the student's
      // code could carry state from one test into the next). The test's clock starts once the
      // last one's server is gone (its ending may take a second: not this test's time).
      // Its CPU limit (RLIMIT_CPU) says whether the code was too slow; the wall clock is only a
      // backstop, with room for a wait for a core (wall_backstop: 2 × the limit + 5 s), and a
      // server starved at it by a busy machine is the grader's failure (MachineTooBusy), not a 0.
      probe.stop();
      const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                                                    std::chrono::duration<double>(wall_backstop(limits.cpu_seconds)));
      try {
        const CheckResult c = t.check->run(probe, deadline);
        r.passed = c.passed;
        r.output = c.output;
      } catch (const MachineTooBusy& e) {
        throw MachineTooBusy("test " + t.name + ": " + e.what());
      } catch (const ProbeFailure& e) {
        r.output = std::string(1, static_cast<char>(std::toupper(e.what()[0]))) + (e.what() + 1);
        if (r.output.back() != '.' && r.output.find('\n') == std::string::npos) r.output += ".";
        // The test's hint is about wrong numbers: it helps a run too slow to finish (a step size
        // that shrinks without end) and one that its numbers stopped (a step of 0, a control that
        // keeps a rejected step), not one that crashed, threw or ran out of memory.
        // An assignment may say what running out of time usually means there (a cloth's sweeps that
        // run until the sticks are exact, rather than constraints.iterations times).
        const std::string& hint = e.out_of_time() && !a.timeout_hint.empty() ? a.timeout_hint : t.hint;
        // Out of time after a flood of prints (the message then begins "your code printed N MB (L
        // lines)"): the prints are the likelier cause, said first; the hint is the other. The cloth
        // solution with one printf in project_stick timed out so, blamed on a loop alone.
        if (e.printed_a_lot())
          r.output += "\nPrinting that much is slow (each print is written out at once, to be shown if the code crashes): "
                      "print less (or only once) and grade again." +
                      (hint.empty() ? std::string() : " If it still times out, this usually means: " + hint);
        else if (!hint.empty() && (e.out_of_time() || e.stopped_the_run()))
          r.output += "\nThis usually means: " + hint;
      }
      // What the student's code printed during this test, its server stopped so that all of it
      // has been read (an unflushed std::cout too); a crash's message has shown it already.
      probe.stop();
      r.printed = probe.printed();
    }
    r.score = r.passed ? r.max_score : 0;
    result.score += r.score;
    result.tests.push_back(r);
  }
  probe.stop();
  // A right answer that is also what code that does nothing gives counts only with one of the
  // tests it names passed too (by the same code, before this rule).
  std::vector<bool> passed_alone;
  for (size_t k = 0; k < a.tests.size(); ++k) passed_alone.push_back(result.tests[2 + k].passed);  // (after files and build)
  for (size_t k = 0; k < a.tests.size(); ++k) {
    const TestCase& t = a.tests[k];
    TestResult& r = result.tests[2 + k];
    if (!r.passed || t.counts_with_one_of.empty()) continue;
    bool shown_to_work = false;
    for (size_t j = 0; j < a.tests.size(); ++j)
      for (const auto& gate : t.counts_with_one_of) shown_to_work = shown_to_work || (a.tests[j].name == gate && passed_alone[j]);
    if (shown_to_work) continue;
    r.passed = false;
    result.score -= r.score;
    r.score = 0;
    r.output += fmt::format("\nRight, but code that does nothing gives this answer too: it counts once one of these "
                            "passes as well: {}.",
                            fmt::join(t.counts_with_one_of, ", "));
  }
  // A failed test shows what the student's code printed during it, below what was measured: their
  // own debugging of a wrong answer. A passing test does not (results.json stays small). In the
  // test's own output it is shown when the test is (its visibility), and the terminal's summary
  // shows it made safe (terminal_safe), as it does a crash's output.
  for (size_t k = 2; k < result.tests.size(); ++k) {  // (files' and build's outputs are bounded where they are made)
    TestResult& r = result.tests[k];
    r.output = bounded(r.output, kTestTextBytes);
    if (!r.passed && !r.printed.empty()) r.output += (r.output.ends_with('\n') ? "" : "\n") + r.printed;
  }
  if (built.ok && !o.plugin_out.empty()) {
    // The student's code ran as the user that owns the build's folder (and, without a sandbox,
    // could reach it): the plug-in there must still be a file, not a link to one of the grader's.
    // (Every process of that user has ended: nothing can change it between this look and the copy.)
    std::error_code error;
    if (!fs::is_regular_file(fs::symlink_status(built.plugin, error)))
      throw std::runtime_error(built.plugin + ": the built plug-in is no longer a file (the submission's code replaced "
                                              "it); --plugin-out is not written");
    copy_file_told(built.plugin, o.plugin_out);  // (a full disk said "Input/output error" of --plugin-out)
  }

  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - began).count();
  // The overall message is shown to students at once, whatever the tests' visibility: it counts
  // only the tests they see now. (Gradescope hides the total while a test is hidden; totals in the
  // message would tell a student how the hidden ones went.)
  long passed = 0, shown = 0, shown_passed = 0;
  double shown_score = 0, shown_max = 0;
  for (size_t i = 2; i < result.tests.size(); ++i) {
    const TestResult& t = result.tests[i];
    passed += t.passed;
    if (t.visibility != "visible") continue;
    ++shown, shown_passed += t.passed, shown_score += t.score, shown_max += t.max_score;
  }
  const long not_shown = static_cast<long>(a.tests.size()) - shown;
  // (Counted by visibility: a visible test among the hidden ones was counted "never shown", an
  // after_published one "shown after the due date".)
  const bool all_hidden = a.not_given_by_visibility.size() == 1 && a.not_given_by_visibility.count("hidden");
  const std::string not_run = a.hidden_not_given == 0 ? ""
                              : all_hidden ? fmt::format(" ({} hidden test{} not run here)", a.hidden_not_given,
                                                         a.hidden_not_given == 1 ? "" : "s")
                                           : fmt::format(" ({} of the instructor's tests not run here: {})",
                                                         a.hidden_not_given, a.not_given_when());
  if (not_shown == 0) {
    result.output = fmt::format("{}: {} of {} points; {} of {} tests passed{}.", a.title, result.score, result.max_score,
                                passed, a.tests.size(), not_run);
  } else {
    result.output = fmt::format("{}: {} of {} points on the {} tests shown now; {} of them passed. {} more test{} "
                                "{} graded and shown later, or not at all.",
                                a.title, shown_score, shown_max, shown, shown_passed, not_shown, not_shown == 1 ? "" : "s",
                                not_shown == 1 ? "is" : "are");
    result.totals = fmt::format("All tests: {} of {} points; {} of {} tests passed{}.", result.score, result.max_score,
                                passed, a.tests.size(), not_run);
  }
  // (Or there and not taken: a link, a file over 1 MB. "Missing" alone sent a student looking for
  // a file they could see.)
  if (!files.passed) result.output += " A handed-in file is missing or cannot be taken: see \"files\".";
  else if (!build.passed) result.output += " The submission does not compile: see \"build\".";
  return result;
}

nlohmann::json gradescope_json(const GradeResult& r) {
  nlohmann::json tests = nlohmann::json::array();
  for (const auto& t : r.tests)
    tests.push_back({{"name", t.name + ": " + t.title},
                     {"number", t.number},
                     {"score", t.score},
                     {"max_score", t.max_score},
                     {"status", t.passed ? "passed" : "failed"},
                     {"output", t.output},
                     {"visibility", t.visibility}});
  return {{"score", r.score},
          {"max_score", r.max_score},
          {"execution_time", std::round(r.seconds * 1000) / 1000},
          {"output", r.output},
          {"visibility", "visible"},
          {"stdout_visibility", "hidden"},
          {"extra_data", {{"compiled", r.compiled}, {"assignment", r.assignment}}},
          {"tests", tests}};
}

// What the student's code wrote (its exception messages, its output), made safe for a terminal:
// control characters but the line break and the tab (an escape sequence could clear the
// instructor's screen, or rewrite what the lines above say) become '?', as do C1 controls.
std::string terminal_safe(const std::string& text) {
  std::string safe;
  safe.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if ((c < 0x20 && c != '\n' && c != '\t') || c == 0x7f) {
      safe += '?';
    } else if (c == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
               static_cast<unsigned char>(text[i + 1]) <= 0x9f) {
      safe += '?', ++i;  // U+0080 … U+009F
    } else {
      safe += text[i];
    }
  }
  return safe;
}

bool looks_packed(const std::string& file_name) {
  std::string name = file_name;
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const char* packed : {".zip", ".tar", ".tar.gz", ".tgz", ".tar.xz", ".txz", ".tar.bz2", ".tbz2", ".gz", ".7z", ".rar"})
    if (name.size() > std::string(packed).size() && name.ends_with(packed)) return true;
  return false;
}

std::string text_summary(const GradeResult& r) {
  std::string text = terminal_safe(r.output) + fmt::format(" ({:.1f} s)\n", r.seconds);
  if (!r.totals.empty()) text += r.totals + "\n";
  text += "\n";
  const std::string* shown = nullptr;  // the last failed test's output, as printed
  for (const auto& t : r.tests) {
    text += fmt::format("{:<5} {:<4} {:>5}/{:<5} {}: {}\n", t.passed ? "PASS" : "FAIL", t.number, t.score, t.max_score,
                        t.name, t.title);
    if (!t.passed && shown && *shown == t.output) {
      // (Every test of a submission that does not compile says "Not run: ..." alike: once, under the
      // first, not twenty times after the compiler's own words.)
      text += "             (as above)\n";
    } else if (!t.passed) {
      shown = &t.output;
      std::string indented;
      size_t start = 0;
      while (start < t.output.size()) {
        const size_t end = t.output.find('\n', start);
        indented += "             " + terminal_safe(t.output.substr(start, end == std::string::npos ? std::string::npos : end - start)) + "\n";
        if (end == std::string::npos) break;
        start = end + 1;
      }
      text += indented;
    }
  }
  return text;
}

nlohmann::json failed_json(const std::string& assignment, const std::string& why) {
  return {{"score", 0},
          {"max_score", 0},
          {"execution_time", 0},
          {"output", "motus grade could not finish grading " + assignment + ": " + why +
                         ". This is a fault of the grader, not of the submission: tell your instructor."},
          {"visibility", "visible"},
          {"extra_data", {{"internal_error", true}}},
          {"tests", nlohmann::json::array()}};
}

std::string results_text(const nlohmann::json& results) {
  return results.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";
}

}  // namespace motus::grade
