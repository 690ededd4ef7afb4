#pragma once
// Running a student's code where it can do no harm: in its own process, as an unprivileged
// user, inside bubblewrap (no network, a read-only system, only the files it is given, a
// small size-limited tmpfs), with limits on CPU time, address space, processes, file size,
// descriptors, locked memory and message queues, no core files, and a wall-clock kill. Its
// standard error (where its standard output goes too, in the probe server) is kept up to a cap.
//
// On Debian 12 without cgroup v2 these are the tools there are: bubblewrap for namespaces and
// mounts, setrlimit for the limits, setresuid for the user (the grader does the last two
// itself, in the child, before it starts bwrap — no shell, no prlimit or setpriv programs), and
// the probe server's own seccomp filter (server_filter.hpp) for what the limits do not count.
#include <sys/types.h>

#include <chrono>
#include <stdexcept>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "motus/grade/wall_timeout.hpp"

namespace motus::grade {

struct Limits {
  double cpu_seconds = 10;   // RLIMIT_CPU, in whole seconds (rounded up); the wall clock is the caller's deadline (wall_backstop)
  long memory_mb = 512;      // RLIMIT_AS
  long file_mb = 64;         // RLIMIT_FSIZE
  int processes = 64;        // RLIMIT_NPROC, for this sandbox's own user
  // RLIMIT_NOFILE: each descriptor can hold kernel memory outside the address space (a socket's
  // queued bytes, up to 200 kB): 10,000 socket pairs held 2 GB under the machine's own 20,000.
  int descriptors = 256;
  // RLIMIT_MEMLOCK and RLIMIT_MSGQUEUE: set, not inherited from whoever started the grader (io_uring's
  // rings and POSIX message queues are charged to them, outside the address space).
  long locked_mb = 8;
  long queue_kb = 800;
  long tmpfs_mb = 64;        // the writable /tmp
  size_t output_bytes = 64 * 1024;  // standard error kept: its first and last halves (the middle is read and dropped)
};

struct Mount {
  std::string host, inside;
  bool writable = false;
};

struct SandboxSpec {
  std::vector<std::string> argv;  // argv[0]: a path inside the sandbox
  std::vector<Mount> mounts;      // besides /usr (read-only), /proc, /dev and /tmp
  std::string workdir = "/tmp";
  bool writable_tmp = true;       // false: /tmp is there, empty and read-only (the probe server writes no file)
  bool isolate = true;            // false: --no-sandbox (limits and user only, no bubblewrap)
  uid_t uid = 0;                  // the user it runs as (a SandboxUser's)
  // Asked at least every 0.1 s while the grader waits for it: true (Ctrl-C) ends the wait, and
  // the process is killed (interrupted() then true). Its own process group gets no Ctrl-C.
  std::function<bool()> stop;
};

// Grading stopped by `stop` (Ctrl-C): no result to report.
class GradingInterrupted : public std::runtime_error {
public:
  GradingInterrupted() : std::runtime_error("grading interrupted") {}
};

// The unprivileged users sandboxes run as, when the grader runs as root.
constexpr uid_t kFirstUid = 61000, kUsers = 256;

// A user for the sandboxes of one grading, which no other grading on this machine has at the
// same time (a lock file per user): RLIMIT_NPROC counts per user, and the grader ends every
// process of its sandboxes' user when one is done. Without root it is the grader's own user.
class SandboxUser {
public:
  SandboxUser();  // throws std::runtime_error when every user is taken
  ~SandboxUser();
  SandboxUser(const SandboxUser&) = delete;
  SandboxUser& operator=(const SandboxUser&) = delete;
  uid_t uid() const { return uid_; }

private:
  uid_t uid_;
  int lock_ = -1;
};

// The wall clock is a backstop, not the limit: the CPU limit (RLIMIT_CPU) decides whether the
// student's code (or the compiler) was too slow, and a process waiting for a core on a busy machine
// must not be killed for it. The wall-clock deadline for `cpu_seconds` of CPU: 2 × it + 5 s.
double wall_backstop(double cpu_seconds);
// The whole seconds RLIMIT_CPU holds for `cpu_seconds` (it counts in seconds: rounded up).
double cpu_limit_seconds(double cpu_seconds);

// How a sandboxed process ended.
struct Ending {
  bool exited = false;
  int status = 0;       // exit status, when it exited
  int signal = 0;       // the signal that killed it, else 0
  bool timed_out = false;  // killed by us at its deadline
  TimeUse use;             // when timed out: what it did with its time, measured before it was killed
  // When timed out at the backstop: the caller's judgement of it (judge_wall_timeout), for describe.
  std::optional<WallVerdict> verdict;
  // All it wrote on standard error (where the probe server's standard output goes too), the bytes
  // past the cap that were read and dropped included, and the line breaks among them.
  size_t printed_bytes = 0, printed_lines = 0;
  // One phrase: "exited with status 3", "killed by SIGSEGV", "timed out after 10 s of CPU",
  // "timed out after 25 s waiting, not computing", "ran out of its 512 MB". Out of time after
  // printing a lot (printed_a_lot), it begins with that: "printed 132 MB (11,159,655 lines) and
  // timed out after 10 s of CPU" (the grader then says that printing is slow: ProbeFailure::printed_a_lot).
  std::string describe(const Limits& limits, double wall_seconds) const;
  // Whether it ended for want of time: its deadline, or its CPU limit.
  bool out_of_time(const Limits& limits, double wall_seconds) const;
  // Whether it printed kSlowPrintLines lines or kSlowPrintBytes bytes, or more, for each second of
  // its CPU limit (cpu_limit_seconds: 1,000,000 lines or 10 MB at the default 10 s).
  bool printed_a_lot(const Limits& limits) const;
};

// How much printing the message of a test out of time names first, as the likelier cause, per
// second of the CPU limit. The probe server's standard output is unbuffered (a printf just before a
// crash is not lost), so each print is a write to a pipe that the grader reads: the cloth solution
// with one printf in project_stick printed 11.2 million lines (132 MB) in its 10 s of CPU, about
// 0.9 µs a line (its 120 steps wanted 17.8 million), and timed out. 100,000 lines a second of the
// limit is then about a tenth of the CPU the test had, and far more than anyone reads; 1 MB is as
// many prints of 10 bytes with no line break (std::cout << x << ' ' writes each piece at once).
constexpr size_t kSlowPrintBytes = size_t(1) << 20, kSlowPrintLines = 100000;
// "132 MB (11,159,655 lines)", "977 kB (100,000 lines)", "12 bytes (1 line)", "10 MB (all on one line)".
std::string printed_amount(size_t bytes, size_t lines);

class SandboxProcess {
public:
  // Starts it. Throws std::runtime_error when it cannot be started at all.
  SandboxProcess(const SandboxSpec& spec, const Limits& limits);
  ~SandboxProcess();  // kills it if it still runs
  SandboxProcess(const SandboxProcess&) = delete;
  SandboxProcess& operator=(const SandboxProcess&) = delete;

  // One line to its standard input, waiting until `deadline` (reading what it writes meanwhile:
  // a program that stops reading cannot hold the grader); false when it is gone, at the deadline
  // (then timed_out() is true) or when the spec's `stop` said so (interrupted()).
  bool write_line(const std::string& line, std::chrono::steady_clock::time_point deadline);
  // Its next line of standard output, waiting until `deadline`; nullopt at end of file, at the
  // deadline (then timed_out() is true), or when the line is longer than `max_bytes` (then
  // line_too_long() is true: what it wrote is read no further, and only it can end its waits).
  std::optional<std::string> read_line(std::chrono::steady_clock::time_point deadline, size_t max_bytes = kMaxLineBytes);
  bool line_too_long() const { return line_too_long_; }
  // The longest line read_line ever takes (a run's reply: serve records at most 5 million numbers).
  static constexpr size_t kMaxLineBytes = size_t(64) << 20;
  bool timed_out() const { return timed_out_; }
  // Whether a wait ended because the spec's `stop` said so.
  bool interrupted() const { return interrupted_; }
  // Waits for it to end by itself until `deadline`, then kills it; every process it made
  // ends with it.
  Ending finish(std::chrono::steady_clock::time_point deadline);
  // Kills it now.
  Ending kill();
  // What it wrote on standard error, once it has ended: all of it, or past the cap its first
  // half and its last half, "…" on a line of its own between them.
  const std::string& errors() const { return errors_; }

private:
  // Reads its output (and writes what write_line has pending) until `until` holds, its output
  // ends, the deadline passes or `stop` says so.
  enum class Until { line, written, end };
  void pump(std::chrono::steady_clock::time_point deadline, Until until);
  Ending reap(bool killed);
  void keep_errors(const char* data, size_t n);
  // Where the first line in out_buffer_ ends (its '\n'), or npos: each byte is looked at once
  // (a search of the whole buffer after every read made a long line's reading quadratic).
  size_t line_end();
  size_t error_tail_room() const { return error_cap_ / 2; }  // (the cap's last half; its first is the rest)

  pid_t pid_ = -1;
  uid_t uid_ = 0;
  int in_ = -1, out_ = -1, err_ = -1;
  std::string out_buffer_, errors_;
  size_t scanned_ = 0;  // out_buffer_'s bytes before this hold no '\n' (or it is there: line_end)
  size_t line_cap_ = kMaxLineBytes;
  bool line_too_long_ = false;
  std::string errors_tail_;  // (past the cap's first half: the newest, see keep_errors)
  std::string pending_;     // what write_line has still to write, from pending_at_
  size_t pending_at_ = 0;
  bool write_failed_ = false;
  size_t error_cap_;
  bool errors_cut_ = false;
  size_t printed_bytes_ = 0, printed_lines_ = 0;  // (all it wrote on standard error: Ending's)
  bool timed_out_ = false;
  std::function<bool()> stop_;
  bool interrupted_ = false;
  std::optional<Ending> ending_;
  std::chrono::steady_clock::time_point started_;
  // Each of its tasks' wait for a core as last seen (by task id), sampled while the grader waits
  // for it (kSampleEvery): the deadline's measure counts the waits of processes already ended.
  static constexpr std::chrono::milliseconds kSampleEvery{250};
  TaskWaits run_delays_;
  std::chrono::steady_clock::time_point sampled_at_;
};

// Why the user `uid` (no supplementary groups) cannot reach `host` — a folder on the way, as given
// or as its links lead, it may not pass through, or the file it may not read — or "". As root the
// grader runs the student's code (and bubblewrap) as such a user, who must reach every folder it
// mounts or reads: a TMPDIR under a 0700 folder of root's gave every student 0, "does not compile".
std::string unreachable_for(uid_t uid, const std::string& host);

// Whether a sandbox can be made here, and if not the one line that says why.
std::optional<std::string> sandbox_unavailable();

// The bubblewrap program ($MOTUS_BWRAP, else where Debian puts it), or "" when it is not there.
std::string bubblewrap_program();

}  // namespace motus::grade
