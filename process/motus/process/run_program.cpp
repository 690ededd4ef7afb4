#include "motus/process/run_program.hpp"

#include <atomic>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <sstream>

extern char** environ;

namespace motus::process {

std::string find_program(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) dir.assign(1, '.');  // (not = ".": GCC 12 warns falsely, PR105651)
    const std::filesystem::path candidate = std::filesystem::path(dir) / program;
    std::error_code error;
    if (std::filesystem::is_regular_file(candidate, error) && ::access(candidate.c_str(), X_OK) == 0) {
      // (Absolute: run_program changes folder before it starts the program.)
      const std::filesystem::path absolute = std::filesystem::absolute(candidate, error);
      if (!error) return absolute.string();
    }
  }
  return "";
}

namespace {
// The programs being waited for, for kill_running_programs (a few at once: grade's jobs). Lock-free
// atomics, so that a signal handler may read them.
constexpr int kSlots = 64;
std::atomic<pid_t> g_running[kSlots];
static_assert(std::atomic<pid_t>::is_always_lock_free);

struct Running {
  int slot = -1;
  explicit Running(pid_t pid) {
    for (int k = 0; k < kSlots && slot < 0; ++k) {
      pid_t free = 0;
      if (g_running[k].compare_exchange_strong(free, pid)) slot = k;
    }
  }
  ~Running() {
    if (slot >= 0) g_running[slot].store(0);
  }
  Running(const Running&) = delete;
  Running& operator=(const Running&) = delete;
};
}  // namespace

namespace {
std::atomic<bool> g_stopping{false};
static_assert(std::atomic<bool>::is_always_lock_free);

// Waits for `pid` once stop_running_programs was called: kTerminateGraceMs for it to end (it has had
// SIGTERM), then SIGKILL.
bool reap_stopped(pid_t pid, int& raw) {
  ::kill(pid, SIGTERM);  // (again: it may have started after the handler's)
  for (int waited = 0; waited < kTerminateGraceMs; waited += 10) {
    const pid_t ended = ::waitpid(pid, &raw, WNOHANG);
    if (ended == pid) return true;
    if (ended < 0 && errno != EINTR) return false;
    const timespec pause{0, 10'000'000};
    ::nanosleep(&pause, nullptr);
  }
  ::kill(pid, SIGKILL);
  while (::waitpid(pid, &raw, 0) < 0)
    if (errno != EINTR) return false;
  return true;
}
}  // namespace

void stop_running_programs() noexcept {
  g_stopping.store(true);
  for (auto& running : g_running)
    if (const pid_t pid = running.load(); pid > 0) ::kill(pid, SIGTERM);
}

bool stopping() noexcept { return g_stopping.load(); }

void kill_running_programs() noexcept {
  for (auto& running : g_running)
    if (const pid_t pid = running.load(); pid > 0) ::kill(pid, SIGKILL);
}

std::string Outcome::not_started(const std::string& name, const std::string& path) const {
  return name + " (" + path + ") could not be started (" + std::strerror(error) + ")";
}

Outcome run_program(const std::vector<std::string>& argv_in, const std::string& folder, const std::string& log) {
  Outcome outcome;
  if (argv_in.empty()) return outcome;
  std::vector<std::string> args = argv_in;
  // The program's path is taken from here, before the change of folder below (in which a relative
  // path would name another file, or none).
  std::string program = args[0];
  if (!folder.empty() && !program.empty() && program.front() != '/') {
    std::error_code error;
    const std::filesystem::path absolute = std::filesystem::absolute(program, error);
    if (!error) program = absolute.string();
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  if (!log.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  if (!folder.empty()) posix_spawn_file_actions_addchdir_np(&actions, folder.c_str());
  // The program gets SIGPIPE's default action back: motus ignores it (a write to a reader that
  // went away fails and is reported), and an ignored signal stays ignored across exec.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  const int error = posix_spawn(&pid, program.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  if (error != 0) {
    outcome.error = error;
    return outcome;
  }
  outcome.started = true;
  const Running running(pid);
  int raw = 0;
  // (Once stopping, a program is not waited for to finish: also one started after the interrupt,
  // or whose registration the handler's SIGTERM missed — g_stopping is read after registering.)
  if (g_stopping.load()) {
    if (!reap_stopped(pid, raw)) return outcome;
  } else {
    while (::waitpid(pid, &raw, 0) < 0) {
      if (errno != EINTR) return outcome;
      if (g_stopping.load()) {  // (the interrupt's EINTR: the handler has sent it SIGTERM)
        if (!reap_stopped(pid, raw)) return outcome;
        break;
      }
    }
  }
  if (WIFEXITED(raw)) outcome.status = WEXITSTATUS(raw);
  if (WIFSIGNALED(raw)) outcome.signal = WTERMSIG(raw);
  return outcome;
}

}  // namespace motus::process
