#pragma once
// Running the built `motus` binary as a user would, for the command-line tests: a fresh
// temporary folder per test, the command's exit status, standard output and standard
// error. MOTUS_BINARY and MOTUS_SCENES_DIR come from tests/CMakeLists.txt.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <signal.h>

#include <cerrno>
#include <cstring>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace motus_test {

namespace fs = std::filesystem;

const std::string kMotus = MOTUS_BINARY;
const std::string kScenes = MOTUS_SCENES_DIR;

std::string scene(const std::string& name) { return (fs::path(kScenes) / (name + ".json")).string(); }

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

// A fresh folder per test (ctest may run tests in parallel).
class TempDir {
public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    std::replace(name.begin(), name.end(), '/', '_');
    path_ = fs::temp_directory_path() / ("motus_test_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  fs::path operator/(const std::string& file) const { return path_ / file; }
  const fs::path& path() const { return path_; }

private:
  fs::path path_;
};

struct Result {
  int status = -1;  // the exit status; 128 + N when killed by signal N
  std::string out, err;
};

// This process's environment with `environment` ("NAME=value") replacing or adding its names;
// under the sanitizers, where their reports go.
inline std::vector<std::string> child_environment(std::vector<std::string> environment) {
#ifdef MOTUS_SANITIZE
  // Under the sanitizers their reports go to files (docs/testing.md), so that a test counting
  // the lines of motus's standard error counts motus's own. These replace any inherited copies:
  // of two entries with one name, the first is the one a program reads.
  environment.push_back("ASAN_OPTIONS=log_path=" MOTUS_SANITIZER_LOGS "/asan");
  environment.push_back("UBSAN_OPTIONS=print_stacktrace=1:log_path=" MOTUS_SANITIZER_LOGS "/ubsan");
  environment.push_back("LSAN_OPTIONS=suppressions=" MOTUS_LSAN_SUPPRESSIONS);
#endif
  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e) {
    const std::string entry = *e, name = entry.substr(0, entry.find('='));
    const bool replaced = std::any_of(environment.begin(), environment.end(),
                                      [&](const std::string& mine) { return mine.substr(0, mine.find('=')) == name; });
    if (!replaced) env_strings.push_back(entry);
  }
  env_strings.insert(env_strings.end(), environment.begin(), environment.end());
  return env_strings;
}

// Runs PROGRAM ARGS... directly (no shell), with standard input from /dev/null and standard
// output and error captured in files of `dir`. `environment` entries ("NAME=value") are set
// on top of this process's environment.
inline Result run_program(const TempDir& dir, const std::string& program, const std::vector<std::string>& args,
                          const std::vector<std::string>& environment = {}) {
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<std::string> argv_strings = {program};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_strings = child_environment(environment);
  std::vector<char*> envp;
  for (auto& e : env_strings) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  Result r;
  if (spawned != 0) {
    r.err = program + ": cannot be started: " + std::strerror(spawned);
    return r;
  }
  int raw = 0;
  while (waitpid(pid, &raw, 0) < 0 && errno == EINTR) {
  }
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : WIFSIGNALED(raw) ? 128 + WTERMSIG(raw) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

// Where a motus started by run_motus_with reads and writes: files by path, or standard output
// to an open descriptor (out_fd ≥ 0), and the folder it runs in ("": this process's).
struct MotusFiles {
  std::string in = "/dev/null", out = "/dev/null", err = "/dev/null", folder;  // (kClosed: the descriptor is closed)
  int out_fd = -1;
};
inline const std::string kClosed = "(closed)";

// Starts `motus ARGS...` with those files and returns at once: its pid (-1: it did not start).
inline pid_t start_motus_with(std::vector<std::string> args, const MotusFiles& files) {
  args.insert(args.begin(), kMotus);
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!files.folder.empty()) posix_spawn_file_actions_addchdir_np(&actions, files.folder.c_str());
  posix_spawn_file_actions_addopen(&actions, 0, files.in.c_str(), O_RDONLY, 0);
  if (files.out_fd >= 0)
    posix_spawn_file_actions_adddup2(&actions, files.out_fd, 1);
  else if (files.out == kClosed)
    posix_spawn_file_actions_addclose(&actions, 1);
  else
    posix_spawn_file_actions_addopen(&actions, 1, files.out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (files.err == kClosed)
    posix_spawn_file_actions_addclose(&actions, 2);
  else
    posix_spawn_file_actions_addopen(&actions, 2, files.err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, kMotus.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return spawned == 0 ? pid : -1;
}

// The same, waiting for it: its raw wait status (-1: it did not start).
inline int run_motus_with(const std::vector<std::string>& args, const MotusFiles& files) {
  const pid_t pid = start_motus_with(args, files);
  if (pid < 0) return -1;
  int raw = 0;
  while (waitpid(pid, &raw, 0) < 0 && errno == EINTR) {
  }
  return raw;
}

// Waits (up to 60 s) until process `pid` catches `signal`, as /proc/PID/status's SigCgt mask
// shows: from then on a signal reaches its handler, not the default action.
inline bool wait_until_catching(pid_t pid, int signal) {
  for (int i = 0; i < 6000; ++i) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("SigCgt:", 0) == 0 && (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1) & 1)) return true;
    ::usleep(10000);
  }
  return false;
}

// Waits up to `seconds` for process `pid` to end, its wait status in `raw`; if it has not ended
// by then, kills it, reaps it and returns false (a test that then fails leaves nothing running).
inline bool ended_within(pid_t pid, int seconds, int& raw) {
  for (int i = 0; i < 10 * seconds; ++i) {
    if (::waitpid(pid, &raw, WNOHANG) == pid) return true;
    ::usleep(100000);
  }
  ::kill(pid, SIGKILL);
  ::waitpid(pid, &raw, 0);
  return false;
}

// Runs `motus ARGS...` as above.
inline Result run_motus(const TempDir& dir, const std::vector<std::string>& args,
                        const std::vector<std::string>& environment = {}) {
  return run_program(dir, kMotus, args, environment);
}

// Ctrl-C in the middle of drawing: runs `motus ARGS...` in a process group of its own (as a
// shell runs a job), with a stand-in for gnuplot first on PATH (dir/bin/gnuplot) that leaves a
// mark, "plotting-started", in the folder it is started in and then waits; as soon as a folder
// of `dir` has the mark, the whole group gets SIGINT. The result as run_program gives it (its
// output in dir/stdout.txt and dir/stderr.txt), or status -1 when no plotting began in 20 s.
// `ignoring_interrupts`: the stand-in ignores SIGINT, as a gnuplot that caught the same Ctrl-C and
// hung did (it is ended only by motus, or by `sleep 30` ending).
inline Result interrupt_motus_while_plotting(const TempDir& dir, const std::vector<std::string>& args,
                                             bool ignoring_interrupts = false) {
  const fs::path bin = dir / "bin", out = dir / "stdout.txt", err = dir / "stderr.txt";
  fs::create_directories(bin);
  write_file(bin / "gnuplot", std::string("#!/bin/sh\n") + (ignoring_interrupts ? "trap '' INT\n" : "") +
                                  "touch \"$PWD/plotting-started\"\nexec sleep 30\n");
  fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::vector<std::string> argv_strings = {kMotus};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_strings) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_strings = child_environment({"PATH=" + bin.string() + ":/usr/bin:/bin"});
  std::vector<char*> envp;
  for (auto& e : env_strings) envp.push_back(e.data());
  envp.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, kMotus.c_str(), &actions, &attributes, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  Result r;
  if (spawned != 0) {
    r.err = kMotus + ": cannot be started: " + std::strerror(spawned);
    return r;
  }
  bool plotting = false;
  for (int i = 0; i < 4000 && !plotting; ++i) {
    for (const auto& e : fs::directory_iterator(dir.path()))
      if (fs::exists(e.path() / "plotting-started")) plotting = true;
    if (!plotting) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(-pid, plotting ? SIGINT : SIGKILL);  // Ctrl-C: the whole foreground group, motus and its plotting
  int raw = 0;
  while (waitpid(pid, &raw, 0) < 0 && errno == EINTR) {
  }
  r.status = !plotting ? -1 : WIFEXITED(raw) ? WEXITSTATUS(raw) : WIFSIGNALED(raw) ? 128 + WTERMSIG(raw) : -1;
  r.out = read_file(out);
  r.err = (plotting ? "" : "no plotting began within 20 s\n") + read_file(err);
  return r;
}

inline long count_lines(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }

// A CSV file's rows after its header, each split at its commas (the files motus writes quote no commas).
inline std::vector<std::vector<std::string>> csv_data_rows(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  while (std::getline(lines, line)) {
    std::vector<std::string> cells;
    std::istringstream cell_stream(line);
    for (std::string cell; std::getline(cell_stream, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

}  // namespace motus_test
