#include "motus/grade/sandbox.hpp"

#include <fcntl.h>
#include <grp.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/file.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "motus/grade/format_seconds.hpp"

namespace fs = std::filesystem;

namespace motus::grade {
namespace {

using detail::format_seconds;

// The processes this user has now (RLIMIT_NPROC counts them all, not only the sandbox's).
long processes_of(uid_t uid) {
  long count = 0;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator("/proc", error)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || !std::all_of(name.begin(), name.end(), ::isdigit)) continue;
    struct stat info {};
    if (::stat(entry.path().c_str(), &info) == 0 && info.st_uid == uid) ++count;
  }
  return count;
}

// Ends every process of a sandbox's user (when the grader is root and the user is the
// sandbox's own): a fork bomb's children may outlive the namespace they were made in for a
// moment, and until they are gone they count against the next sandbox's process limit.
void clear_user(uid_t uid) {
  if (::geteuid() != 0 || uid < kFirstUid) return;
  const pid_t sweeper = ::fork();
  if (sweeper == 0) {
    if (::setresgid(uid, uid, uid) == 0 && ::setresuid(uid, uid, uid) == 0) ::kill(-1, SIGKILL);  // all of this user's
    ::_exit(0);
  }
  if (sweeper > 0)
    while (::waitpid(sweeper, nullptr, 0) < 0 && errno == EINTR) {
    }
  // What is left are zombies for the system to reap; the next sandbox's process limit counts them in.
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> p;
  for (auto& s : strings) p.push_back(s.data());
  p.push_back(nullptr);
  return p;
}

const char* signal_name(int signal) {
  switch (signal) {
    case SIGSEGV: return "SIGSEGV";
    case SIGABRT: return "SIGABRT";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGKILL: return "SIGKILL";
    case SIGXCPU: return "SIGXCPU";
    case SIGXFSZ: return "SIGXFSZ";
    case SIGTERM: return "SIGTERM";
    case SIGPIPE: return "SIGPIPE";
    default: return nullptr;
  }
}

// The first folder on `path` (absolute) the user cannot pass through, or the file at its end it
// cannot read; "" when there is none.
std::string unreachable_along(uid_t uid, const fs::path& path) {
  auto allowed = [uid](const struct stat& st, mode_t user, mode_t group, mode_t other) {
    return st.st_uid == uid ? (st.st_mode & user) != 0 : st.st_gid == uid ? (st.st_mode & group) != 0 : (st.st_mode & other) != 0;
  };
  auto mode = [](const struct stat& st) {
    char text[8];
    std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(st.st_mode & 07777));
    return std::string(text);
  };
  fs::path at = path.root_path();
  for (auto part = path.begin(); part != path.end(); ++part) {
    if (part != path.begin()) at /= *part;
    struct stat st {};
    if (::stat(at.c_str(), &st) != 0) return at.string() + ": " + std::strerror(errno);
    const bool last = std::next(part) == path.end();
    if (S_ISDIR(st.st_mode) && !allowed(st, S_IXUSR, S_IXGRP, S_IXOTH))
      return at.string() + " (mode " + mode(st) + "): the sandbox's user (uid " + std::to_string(uid) +
             ") cannot pass through it" + (last ? "" : " to " + path.string());
    if (last && !S_ISDIR(st.st_mode) && !allowed(st, S_IRUSR, S_IRGRP, S_IROTH))
      return at.string() + " (mode " + mode(st) + "): the sandbox's user (uid " + std::to_string(uid) + ") cannot read it";
  }
  return "";
}

// A process's /proc/PID/stat (or a thread's, …/task/TID/stat) after its name: its fields from
// the third (state) on, split at spaces; empty when it is gone.
std::vector<std::string> stat_fields(const std::string& path) {
  FILE* file = std::fopen(path.c_str(), "re");
  if (!file) return {};
  char text[2048];
  const size_t n = std::fread(text, 1, sizeof text - 1, file);
  std::fclose(file);
  text[n] = '\0';
  const char* after = std::strrchr(text, ')');  // (the name, in parentheses, may hold spaces)
  std::vector<std::string> fields;
  if (!after) return fields;
  std::string field;
  for (const char* c = after + 1; *c; ++c) {
    if (*c == ' ' || *c == '\n') {
      if (!field.empty()) fields.push_back(field), field.clear();
    } else {
      field += *c;
    }
  }
  if (!field.empty()) fields.push_back(field);
  return fields;
}

double field_number(const std::vector<std::string>& fields, size_t number) {  // (number: stat's, from 1)
  return number >= 3 && number - 3 < fields.size() ? std::strtod(fields[number - 3].c_str(), nullptr) : 0;
}

// What `root` and every process under it did with their time. (Its descendants by their parents in
// /proc/*/stat: /proc/PID/task/*/children is not on every kernel.) `run_delays` holds each task's
// (thread's) wait for a core as last seen, by its id, from call to call: a process that ended
// before the deadline takes its schedstat with it, and its wait counts all the same. (A compile's
// cc1plus, waiting for a core on a machine busy with two builds, ended and was reaped by g++; the
// deadline saw only the assembler's wait: "timed out after 125 s waiting, not computing", and the
// reference solution scored 0.) Its CPU time is in its parent's (cutime, cstime) once reaped.
TimeUse measure_tree(pid_t root, double wall, TaskWaits& run_delays) {
  TimeUse use;
  use.wall = wall;
  std::vector<std::pair<pid_t, pid_t>> parents;  // (pid, its parent)
  std::error_code error;
  for (const auto& entry : fs::directory_iterator("/proc", error)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || !std::all_of(name.begin(), name.end(), ::isdigit)) continue;
    const auto fields = stat_fields(entry.path().string() + "/stat");
    if (!fields.empty()) parents.emplace_back(std::stoi(name), static_cast<pid_t>(field_number(fields, 4)));
  }
  std::vector<pid_t> tree = {root};
  for (size_t i = 0; i < tree.size(); ++i)
    for (const auto& [pid, parent] : parents)
      if (parent == tree[i]) tree.push_back(pid);
  const double ticks = static_cast<double>(::sysconf(_SC_CLK_TCK));
  errno = 0;
  const int own_nice = ::getpriority(PRIO_PROCESS, 0);
  const bool own_idle = ::sched_getscheduler(0) == SCHED_IDLE;  // (inherited by the sandbox: not the code's doing)
  bool delay_seen = false, delay_missing = false;
  for (const pid_t pid : tree) {
    const std::string folder = "/proc/" + std::to_string(pid);
    const auto fields = stat_fields(folder + "/stat");
    if (fields.empty()) continue;
    // utime, stime, cutime, cstime: its threads' and its reaped children's.
    use.cpu += (field_number(fields, 14) + field_number(fields, 15) + field_number(fields, 16) + field_number(fields, 17)) / ticks;
    for (const auto& task : fs::directory_iterator(folder + "/task", error)) {
      const auto thread = stat_fields(task.path().string() + "/stat");
      if (thread.empty()) continue;
      use.runnable_now = use.runnable_now || thread[0] == "R";
      const int policy = static_cast<int>(field_number(thread, 41));
      if (field_number(thread, 19) > own_nice || (policy == SCHED_IDLE && !own_idle)) use.lowered_priority = true;
      // schedstat: time on a CPU, time runnable waiting for one (run_delay), in ns; timeslices.
      FILE* file = std::fopen((task.path().string() + "/schedstat").c_str(), "re");
      unsigned long long on_cpu = 0, delay = 0;
      if (file && std::fscanf(file, "%llu %llu", &on_cpu, &delay) == 2) {
        TaskWait& seen = run_delays[static_cast<pid_t>(std::strtol(task.path().filename().c_str(), nullptr, 10))];
        seen.process = pid;
        seen.delay = std::max(seen.delay, static_cast<double>(delay) * 1e-9);  // (an id used again starts from 0)
        delay_seen = true;
      } else {
        delay_missing = true;
      }
      if (file) std::fclose(file);
    }
  }
  use.run_delay = waited_for_a_core(run_delays);
  use.run_delay_known = delay_seen && !delay_missing;
  return use;
}

}  // namespace

double wall_backstop(double cpu_seconds) { return 2 * cpu_seconds + 5; }

double cpu_limit_seconds(double cpu_seconds) { return std::ceil(cpu_seconds); }

// Why the sandbox's user (uid, no supplementary groups) cannot reach `host` for a mount, or "":
// bubblewrap runs as that user, who must pass through every folder on the way and read the
// file (a TMPDIR or an assignment under a 0700 folder of root's gave every student 0 points,
// "does not compile", with bubblewrap's "Permission denied" as the compiler's words).
std::string unreachable_for(uid_t uid, const std::string& host) {
  // The way as given (bubblewrap follows it, links and all), then the way it leads.
  std::error_code error;
  const fs::path canonical = fs::canonical(host, error);
  if (error) return host + ": " + error.message();
  for (const fs::path& path : {fs::absolute(host).lexically_normal(), canonical})
    if (std::string why = unreachable_along(uid, path); !why.empty()) return why;
  return "";
}

SandboxUser::SandboxUser() : uid_(::geteuid()) {
  if (::geteuid() != 0) return;
  const std::string folder = "/run/motus-grade-users";
  ::mkdir(folder.c_str(), 0700);
  for (uid_t u = kFirstUid; u < kFirstUid + kUsers; ++u) {
    const std::string file = folder + "/" + std::to_string(u) + ".lock";
    const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0600);
    if (fd < 0) continue;
    if (::flock(fd, LOCK_EX | LOCK_NB) == 0) {
      uid_ = u;
      lock_ = fd;
      return;
    }
    ::close(fd);
  }
  throw std::runtime_error("every sandbox user (" + std::to_string(kFirstUid) + " to " +
                           std::to_string(kFirstUid + kUsers - 1) + ") is busy with another grading");
}

SandboxUser::~SandboxUser() {
  if (lock_ >= 0) ::close(lock_);  // and the lock with it
}

std::string bubblewrap_program() {
  if (const char* override_path = std::getenv("MOTUS_BWRAP"); override_path && *override_path)  // for tests
    return ::access(override_path, X_OK) == 0 ? override_path : "";
  for (const char* candidate : {"/usr/bin/bwrap", "/bin/bwrap", "/usr/local/bin/bwrap"})
    if (::access(candidate, X_OK) == 0) return candidate;
  return "";
}

bool Ending::out_of_time(const Limits& limits, double wall_seconds) const {
  return timed_out || signal == SIGXCPU ||
         (signal == SIGKILL && limits.cpu_seconds > 0 && wall_seconds >= limits.cpu_seconds);
}

bool Ending::printed_a_lot(const Limits& limits) const {
  const auto seconds = static_cast<size_t>(std::max(1.0, cpu_limit_seconds(limits.cpu_seconds)));
  return printed_bytes >= kSlowPrintBytes * seconds || printed_lines >= kSlowPrintLines * seconds;
}

std::string printed_amount(size_t bytes, size_t lines) {
  auto grouped = [](size_t n) {  // 11,159,655
    std::string digits = std::to_string(n), text;
    for (size_t i = 0; i < digits.size(); ++i) {
      if (i > 0 && (digits.size() - i) % 3 == 0) text += ',';
      text += digits[i];
    }
    return text;
  };
  char size[32];
  const double mb = static_cast<double>(bytes) / (1 << 20);
  if (mb >= 10) std::snprintf(size, sizeof size, "%.0f MB", mb);
  else if (mb >= 1) std::snprintf(size, sizeof size, "%.1f MB", mb);
  else if (bytes >= 1024) std::snprintf(size, sizeof size, "%.0f kB", static_cast<double>(bytes) / 1024);
  else std::snprintf(size, sizeof size, "%zu bytes", bytes);
  return std::string(size) + (lines == 0 ? " (all on one line)" : " (" + grouped(lines) + (lines == 1 ? " line)" : " lines)"));
}

std::string Ending::describe(const Limits& limits, double wall_seconds) const {
  const std::string cpu = format_seconds(cpu_limit_seconds(limits.cpu_seconds));
  // Out of time after a flood of prints: the prints first, the likelier cause (a machine too busy
  // to give it its CPU is not the code's, whatever it printed).
  if (printed_a_lot(limits) && out_of_time(limits, wall_seconds) && !(timed_out && verdict == WallVerdict::starved)) {
    Ending quiet = *this;
    quiet.printed_bytes = quiet.printed_lines = 0;
    return "printed " + printed_amount(printed_bytes, printed_lines) + " and " + quiet.describe(limits, wall_seconds);
  }
  if (timed_out && verdict) {
    switch (*verdict) {
      case WallVerdict::used_its_cpu: return "timed out after " + cpu + " s of CPU";
      case WallVerdict::waiting:
        return "timed out after " + format_seconds(wall_seconds) + " s waiting, not computing (blocked or asleep, it did not use its " +
               cpu + " s of CPU)";
      case WallVerdict::lowered_its_priority:
        return "timed out after " + format_seconds(wall_seconds) + " s: it lowered its own priority (nice, SCHED_IDLE) and was "
               "left waiting for a core";
      case WallVerdict::starved:
        return "was not given its " + cpu + " s of CPU in " + format_seconds(wall_seconds) + " s: the machine was too busy";
    }
  }
  if (timed_out) return "timed out after " + format_seconds(wall_seconds) + " s";
  if (out_of_time(limits, wall_seconds)) return "timed out after " + cpu + " s of CPU";
  if (signal == SIGXFSZ) return "wrote more than its " + std::to_string(limits.file_mb) + " MB to a file";
  if (signal) {
    const char* name = signal_name(signal);
    return std::string("was killed by ") + (name ? name : "signal " + std::to_string(signal));
  }
  return "exited with status " + std::to_string(status);
}

SandboxProcess::SandboxProcess(const SandboxSpec& spec, const Limits& limits)
    : error_cap_(limits.output_bytes), stop_(spec.stop) {
  if (spec.argv.empty()) throw std::invalid_argument("a sandbox needs a program to run");
  // Its whole environment, with or without bubblewrap. (MALLOC_ARENA_MAX: glibc gives each thread
  // that allocates an arena of 64 MB of address space; with two in all, a student's threads are not
  // out of memory at the fifteenth.)
  std::vector<std::string> environment = {"PATH=/usr/bin:/bin", "TMPDIR=/tmp", "HOME=/tmp", "LANG=C.UTF-8",
                                          "MALLOC_ARENA_MAX=2"};
  std::vector<std::string> args;
  if (spec.isolate) {
    const std::string bwrap = bubblewrap_program();
    if (bwrap.empty()) throw std::runtime_error("bubblewrap (bwrap) is not installed: apt-get install bubblewrap");
    // (A user namespace of its own, in which it cannot make another: inside a nested one the code
    // could mount a tmpfs of any size, and fill it.)
    args = {bwrap, "--unshare-all", "--unshare-user", "--disable-userns", "--die-with-parent", "--new-session",
            "--ro-bind", "/usr", "/usr", "--symlink", "usr/lib", "/lib", "--symlink", "usr/lib64", "/lib64",
            "--symlink", "usr/bin", "/bin", "--symlink", "usr/sbin", "/sbin",
            // /dev's own tmpfs read-only (its devices stay usable): unsized, it held as much as
            // half the machine's memory past every limit; scratch space is the sized /tmp.
            "--proc", "/proc", "--dev", "/dev", "--remount-ro", "/dev",
            "--size", std::to_string(limits.tmpfs_mb << 20), "--tmpfs", "/tmp"};
    for (const auto& m : spec.mounts) {
      args.push_back(m.writable ? "--bind" : "--ro-bind");
      args.push_back(m.host);
      args.push_back(m.inside);
    }
    // A tmpfs limits its bytes, not its files: a million empty ones held a gigabyte of the kernel's
    // memory. Code that needs no scratch space gets none.
    if (!spec.writable_tmp) args.insert(args.end(), {"--remount-ro", "/tmp"});
    // The root, bubblewrap's own tmpfs (where the mount points are made), read-only too, last: it
    // is unsized, and code wrote 960 MB of files beside /box/student.so, past its 512 MB.
    args.insert(args.end(), {"--remount-ro", "/"});
    args.insert(args.end(), {"--chdir", spec.workdir, "--clearenv"});
    for (const std::string& e : environment) {
      const size_t equals = e.find('=');
      args.insert(args.end(), {"--setenv", e.substr(0, equals), e.substr(equals + 1)});
    }
    args.emplace_back("--");
  }
  args.insert(args.end(), spec.argv.begin(), spec.argv.end());
  auto argv = pointers(args);
  auto envp = pointers(environment);
  // Everything the child needs is computed here: between fork and exec it only makes system calls.
  const uid_t uid = spec.uid;
  uid_ = uid;
  const bool drop = ::geteuid() == 0;
  const rlim_t cpu = static_cast<rlim_t>(std::ceil(limits.cpu_seconds));
  const rlim_t memory = static_cast<rlim_t>(limits.memory_mb) << 20;
  const rlim_t file = static_cast<rlim_t>(limits.file_mb) << 20;
  const rlim_t descriptors = static_cast<rlim_t>(limits.descriptors);
  const rlim_t locked = static_cast<rlim_t>(limits.locked_mb) << 20, queues = static_cast<rlim_t>(limits.queue_kb) << 10;
  // RLIMIT_NPROC counts every process of the user: those it has now (the grader's own, without
  // root; a killed sandbox's zombies not reaped yet) plus the sandbox's allowance.
  const rlim_t processes = static_cast<rlim_t>(limits.processes + processes_of(uid));
  const std::string workdir = spec.isolate ? "/" : spec.workdir;

  int in[2], out[2], err[2];
  if (::pipe2(in, O_CLOEXEC) || ::pipe2(out, O_CLOEXEC) || ::pipe2(err, O_CLOEXEC))
    throw std::runtime_error(std::string("cannot make pipes: ") + std::strerror(errno));
  started_ = std::chrono::steady_clock::now();
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error(std::string("cannot start a process: ") + std::strerror(errno));
  if (pid_ == 0) {
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    ::dup2(in[0], 0);
    ::dup2(out[1], 1);
    ::dup2(err[1], 2);
    ::close_range(3, ~0U, 0);
    const rlimit cpu_limit{cpu, cpu + 1}, memory_limit{memory, memory}, file_limit{file, file}, no_core{0, 0},
        process_limit{processes, processes}, descriptor_limit{descriptors, descriptors},
        locked_limit{locked, locked}, queue_limit{queues, queues};
    ::setrlimit(RLIMIT_CPU, &cpu_limit);
#ifndef MOTUS_SANITIZE  // AddressSanitizer reserves terabytes of address space: no RLIMIT_AS under it
    ::setrlimit(RLIMIT_AS, &memory_limit);
#else
    (void)memory_limit;
#endif
    ::setrlimit(RLIMIT_FSIZE, &file_limit);
    ::setrlimit(RLIMIT_CORE, &no_core);
    ::setrlimit(RLIMIT_NOFILE, &descriptor_limit);
    ::setrlimit(RLIMIT_MEMLOCK, &locked_limit);
    ::setrlimit(RLIMIT_MSGQUEUE, &queue_limit);
    if (drop) {
      if (::setgroups(0, nullptr) || ::setresgid(uid, uid, uid) || ::setresuid(uid, uid, uid)) ::_exit(126);
    }
    ::setrlimit(RLIMIT_NPROC, &process_limit);
    ::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0);
    // (The grader ignores these; an ignored signal would stay so across exec, and the student's code
    // must be ended by its file-size limit, not see its writes fail.)
    ::signal(SIGPIPE, SIG_DFL);
    ::signal(SIGXFSZ, SIG_DFL);
    if (::chdir(workdir.c_str()) != 0) ::_exit(126);
    ::execve(argv[0], argv.data(), envp.data());
    ::_exit(127);
  }
  ::close(in[0]);
  ::close(out[1]);
  ::close(err[1]);
  in_ = in[1];
  out_ = out[0];
  err_ = err[0];
  // Writes never block: a program that stops reading its input (or shrinks the pipe) would hold
  // the grader in write() past every limit. write_line waits in poll, with the deadline.
  ::fcntl(in_, F_SETFL, ::fcntl(in_, F_GETFL) | O_NONBLOCK);
  ::signal(SIGPIPE, SIG_IGN);  // a sandbox that closed its input must not kill the grader
}

SandboxProcess::~SandboxProcess() {
  if (!ending_) kill();
  for (int fd : {in_, out_, err_})
    if (fd >= 0) ::close(fd);
}

bool SandboxProcess::write_line(const std::string& line, std::chrono::steady_clock::time_point deadline) {
  if (in_ < 0) return false;
  pending_ = line + "\n";
  pending_at_ = 0;
  write_failed_ = false;
  pump(deadline, Until::written);
  const bool written = pending_at_ == pending_.size() && !write_failed_;
  pending_.clear();
  pending_at_ = 0;
  return written;
}

void SandboxProcess::pump(std::chrono::steady_clock::time_point deadline, Until until) {
  const bool want_line = until == Until::line;
  char buffer[65536];
  auto writing = [&] { return in_ >= 0 && !write_failed_ && pending_at_ < pending_.size(); };
  while (out_ >= 0 || err_ >= 0 || writing()) {
    if (want_line && (line_end() != std::string::npos || out_ < 0)) return;
    if (until == Until::written && !writing()) return;
    const auto now = std::chrono::steady_clock::now();
    if (now >= deadline) {
      timed_out_ = true;
      return;
    }
    if (stop_ && stop_()) {
      interrupted_ = true;
      return;
    }
    if (now - sampled_at_ >= kSampleEvery) {  // (its processes' waits for a core, before they end)
      measure_tree(pid_, 0, run_delays_);
      sampled_at_ = now;
    }
    const int wait_ms = static_cast<int>(std::min<long long>(
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now).count() + 1, stop_ ? 100 : 1000));
    pollfd fds[3] = {{out_, POLLIN, 0}, {err_, POLLIN, 0}, {writing() ? in_ : -1, POLLOUT, 0}};
    const int ready = ::poll(fds, 3, wait_ms);
    if (ready < 0 && errno != EINTR) return;
    if (ready <= 0) continue;
    if (fds[2].fd >= 0 && (fds[2].revents & (POLLOUT | POLLERR | POLLHUP))) {
      const ssize_t n = ::write(in_, pending_.data() + pending_at_, pending_.size() - pending_at_);
      if (n > 0) {
        pending_at_ += static_cast<size_t>(n);
      } else if (!(n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))) {
        write_failed_ = true;  // it closed its input (EPIPE), or is gone
      }
    }
    if (fds[1].fd >= 0 && (fds[1].revents & (POLLIN | POLLHUP | POLLERR))) {
      const ssize_t n = ::read(err_, buffer, sizeof buffer);
      if (n <= 0) {
        ::close(err_);
        err_ = -1;
      } else {
        keep_errors(buffer, static_cast<size_t>(n));
      }
    }
    if (fds[0].fd >= 0 && (fds[0].revents & (POLLIN | POLLHUP | POLLERR))) {
      const ssize_t n = ::read(out_, buffer, sizeof buffer);
      if (n <= 0) {
        ::close(out_);
        out_ = -1;
        if (want_line) return;
      } else {
        out_buffer_.append(buffer, static_cast<size_t>(n));
        // A line longer than any answer (or than the one this request can need: read_line's cap).
        const size_t cap = want_line ? line_cap_ : kMaxLineBytes;
        if (out_buffer_.size() > cap && (!want_line || line_end() == std::string::npos || line_end() > cap)) {
          if (until == Until::end) {
            out_buffer_.clear();  // (no line is wanted now: read on and drop, until it ends)
            scanned_ = 0;
          } else {
            line_too_long_ = true;  // (for good: its output is read no further)
            out_buffer_.clear();
            scanned_ = 0;
            ::close(out_);
            out_ = -1;
            return;
          }
        }
      }
    }
  }
}

size_t SandboxProcess::line_end() {
  const size_t end = out_buffer_.find('\n', scanned_);
  scanned_ = end == std::string::npos ? out_buffer_.size() : end;
  return end;
}

std::optional<std::string> SandboxProcess::read_line(std::chrono::steady_clock::time_point deadline, size_t max_bytes) {
  line_cap_ = std::min(max_bytes, kMaxLineBytes);
  pump(deadline, Until::line);
  const size_t end = line_end();
  if (end == std::string::npos) return std::nullopt;
  if (end > line_cap_) {  // (a whole line already read, by an earlier wait, longer than this one may be)
    line_too_long_ = true;
    return std::nullopt;
  }
  std::string line = out_buffer_.substr(0, end);
  out_buffer_.erase(0, end + 1);
  scanned_ = 0;
  return line;
}

Ending SandboxProcess::reap(bool killed) {
  int raw = 0;
  while (::waitpid(pid_, &raw, 0) < 0 && errno == EINTR) {
  }
  Ending e;
  e.timed_out = killed && timed_out_;
  if (WIFSIGNALED(raw)) {
    e.signal = WTERMSIG(raw);
  } else if (WIFEXITED(raw)) {
    e.exited = true;
    e.status = WEXITSTATUS(raw);
    // bubblewrap reports a child killed by signal N as exit status 128 + N.
    const int n = e.status - 128;
    if (n > 0 && n < 32 && signal_name(n)) {
      e.exited = false;
      e.signal = n;
    }
  }
  if (killed && e.signal == SIGKILL && timed_out_) e.timed_out = true;
  clear_user(uid_);
  // What it wrote first, and what it wrote last (the end of a flood is what its author looks for:
  // the prints just before it went wrong), "…" between them where the middle was dropped.
  if (errors_cut_) errors_ += "\n…\n";
  const size_t tail_room = error_tail_room();
  errors_.append(errors_tail_, errors_tail_.size() > tail_room ? errors_tail_.size() - tail_room : 0);
  errors_tail_.clear();
  errors_cut_ = false;
  e.printed_bytes = printed_bytes_;
  e.printed_lines = printed_lines_;
  ending_ = e;
  return e;
}

void SandboxProcess::keep_errors(const char* data, size_t n) {
  // Counted whole, what is dropped too (how much it printed is the message of a test out of time).
  printed_bytes_ += n;
  printed_lines_ += static_cast<size_t>(std::count(data, data + n, '\n'));
  // The cap's first half as it comes, then its last half: the newest bytes, the oldest read and
  // dropped (a flood must not block the sandbox or fill memory). The tail is trimmed once it is
  // twice its room, so that each byte is moved a bounded number of times.
  const size_t head_room = error_cap_ - error_tail_room(), tail_room = error_tail_room();
  const size_t head = std::min(n, head_room - std::min(head_room, errors_.size()));
  errors_.append(data, head);
  data += head, n -= head;
  if (n == 0) return;
  errors_tail_.append(data, n);
  if (errors_tail_.size() > tail_room) errors_cut_ = true;  // (its oldest bytes go: here, or when it ends)
  if (errors_tail_.size() > 2 * tail_room) errors_tail_.erase(0, errors_tail_.size() - tail_room);
}

Ending SandboxProcess::finish(std::chrono::steady_clock::time_point deadline) {
  if (ending_) return *ending_;
  if (in_ >= 0) {
    ::close(in_);
    in_ = -1;
  }
  pump(deadline, Until::end);
  // Its output has ended; it must end too by the deadline: a program that closed its output and
  // waits for ever would hold the grader in waitpid. (WNOWAIT: reap() collects it.)
  while (!timed_out_ && !interrupted_) {
    siginfo_t info{};
    if (::waitid(P_PID, static_cast<id_t>(pid_), &info, WEXITED | WNOHANG | WNOWAIT) == 0 && info.si_pid == pid_) break;
    if (std::chrono::steady_clock::now() >= deadline) {
      timed_out_ = true;
    } else if (stop_ && stop_()) {
      interrupted_ = true;
    } else {
      ::usleep(5000);
    }
  }
  if (timed_out_ || interrupted_) return kill();
  return reap(false);
}

Ending SandboxProcess::kill() {
  if (ending_) return *ending_;
  // At its deadline: what it did with its time, while it is there to be looked at (the caller
  // judges whether it was too slow, waiting, or starved by a busy machine).
  TimeUse use;
  if (timed_out_)
    use = measure_tree(pid_, std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count(), run_delays_);
  ::kill(-pid_, SIGKILL);  // its process group (without bubblewrap, what it started)
  ::kill(pid_, SIGKILL);   // and bubblewrap, whose namespace ends with it
  Ending e = reap(true);
  e.use = use;
  ending_ = e;
  return e;
}

std::optional<std::string> sandbox_unavailable() {
  if (bubblewrap_program().empty())
    return "bubblewrap is not installed (apt-get install bubblewrap); pass --no-sandbox to grade without a sandbox, "
           "knowingly";
  SandboxUser user;
  SandboxSpec spec;
  spec.argv = {"/usr/bin/true"};
  spec.uid = user.uid();
  Limits limits;
  try {
    SandboxProcess probe(spec, limits);
    const Ending e = probe.finish(std::chrono::steady_clock::now() + std::chrono::seconds(10));
    if (e.exited && e.status == 0) return std::nullopt;
    std::string why = probe.errors();
    while (!why.empty() && (why.back() == '\n' || why.back() == ' ')) why.pop_back();
    if (why.find('\n') != std::string::npos) why = why.substr(why.rfind('\n') + 1);
    return "cannot make a sandbox here (bubblewrap: " + (why.empty() ? e.describe(limits, 0) : why) +
           "; user namespaces may be off); pass --no-sandbox to grade without one, knowingly";
  } catch (const std::exception& e) {
    return std::string("cannot make a sandbox here: ") + e.what();
  }
}

}  // namespace motus::grade
