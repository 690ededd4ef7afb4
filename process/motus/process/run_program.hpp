#pragma once
// Starting another program — ffmpeg, gnuplot, zip — directly, with an argument vector: never
// through a shell, so no name, folder or scene field can be read as a command. Standard input
// is /dev/null; standard output and error go to a log file, or stay where motus's are.
#include <string>
#include <vector>

namespace motus::process {

// The absolute path of `program` on $PATH, or "" when there is none. A relative entry of $PATH
// ("bin", or "" for the current folder) is taken from the current folder now: the path is handed
// to run_program, which may start it in another folder, where "bin/gnuplot" is no file.
std::string find_program(const std::string& program);

struct Outcome {
  bool started = false;
  int error = 0;    // when it did not start: why (an errno value: ENOENT, EACCES, ENOEXEC…)
  int status = -1;  // the exit status, when it exited
  int signal = 0;   // the signal that ended it, else 0
  bool ok() const { return started && signal == 0 && status == 0; }
  // For a program that did not start, the words for the user: "gnuplot (/usr/bin/gnuplot) could
  // not be started (Permission denied)" — it wrote nothing of its own to say why.
  std::string not_started(const std::string& name, const std::string& path) const;
};

// Runs argv[0] (a path; a relative one from the current folder, not from `folder`) with the
// arguments argv[1…] in `folder` ("" : here) and waits for it. `log` ("" : inherit) receives its
// standard output and error. Nothing is started when it cannot be (started is false, error says
// why): a program that is not there, not runnable, or a folder or log that cannot be opened.
Outcome run_program(const std::vector<std::string>& argv, const std::string& folder = "", const std::string& log = "");

// An interrupt came (Ctrl-C, SIGTERM, SIGHUP): sends SIGTERM to every program run_program is waiting
// for, and from now on run_program no longer waits for one to finish its work — it gives it
// kTerminateGraceMs to end, then sends SIGKILL (a gnuplot that caught the same Ctrl-C and hung kept
// motus waiting for 30 s, and then its partial report was left). Async-signal-safe: for a handler.
void stop_running_programs() noexcept;
// Whether stop_running_programs was called.
bool stopping() noexcept;
constexpr int kTerminateGraceMs = 1000;

// Sends SIGKILL to every program run_program is waiting for. Async-signal-safe: for a process that
// stops at once from a signal handler (a second Ctrl-C), so that an ffmpeg it started does not go
// on writing after it.
void kill_running_programs() noexcept;

}  // namespace motus::process
