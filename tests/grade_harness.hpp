#pragma once
// What the tests of `motus grade` share (test_grade.cpp, test_grade_hostile.cpp): the
// assignments' own numbers — each test's points in rubric.json, the mistakes it names in
// "catches" — read from their files, and Gradescope's results.json read back.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/socket.h>
#include <netinet/in.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "cli_harness.hpp"

namespace motus_test {

using nlohmann::json;

inline const std::string kAssignments = MOTUS_ASSIGNMENTS_DIR;
inline const std::string kPlugins = MOTUS_TEST_PLUGINS;
inline const std::string kAssignmentPlugins = MOTUS_ASSIGNMENT_PLUGINS;
inline const std::vector<std::string> kAll = {"integrators", "collisions", "cloth"};

// Whether bubblewrap can make a sandbox on this machine.
inline bool sandbox_available() {
  static const bool available = [] {
    TempDir dir;
    const auto r = run_program(dir, "/usr/bin/bwrap", {"--unshare-all", "--ro-bind", "/usr", "/usr", "--symlink",
                                                       "usr/lib64", "/lib64", "--symlink", "usr/lib", "/lib",
                                                       "/usr/bin/true"});
    return r.status == 0;
  }();
  return available;
}

#define NEEDS_SANDBOX() \
  if (!sandbox_available()) GTEST_SKIP() << "no user namespaces here: bubblewrap cannot make a sandbox"

inline json read_json(const fs::path& file) { return json::parse(read_file(file)); }

// Every test definition of an assignment (public and hidden), by name.
inline std::map<std::string, json> definitions(const std::string& assignment) {
  std::map<std::string, json> all;
  for (const char* folder : {"tests", "hidden"})
    for (const auto& entry : fs::directory_iterator(fs::path(kAssignments) / assignment / folder))
      if (entry.path().extension() == ".json") {
        const json file = read_json(entry.path());  // (a named json: a temporary's element would dangle)
        for (const auto& t : file["tests"]) all[t["name"].get<std::string>()] = t;
      }
  return all;
}

inline std::map<std::string, double> points(const std::string& assignment) {
  std::map<std::string, double> p;
  const json rubric = read_json(fs::path(kAssignments) / assignment / "rubric.json");
  for (const auto& t : rubric["tests"])
    p[t["name"].get<std::string>()] = t["points"].get<double>();
  return p;
}

// The tests a result failed, by name ("euler.table: Explicit Euler ..." → "euler.table").
inline std::set<std::string> failed(const json& result) {
  std::set<std::string> names;
  for (const auto& t : result["tests"])
    if (t["status"] == "failed") {
      const std::string name = t["name"].get<std::string>();
      names.insert(name.substr(0, name.find(':')));
    }
  return names;
}

inline const json* test_named(const json& result, const std::string& name) {
  for (const auto& t : result["tests"])
    if (t["name"].get<std::string>().rfind(name + ":", 0) == 0) return &t;
  return nullptr;
}

// Gradescope's results.json fields (docs/grading.md): what every result must have.
inline void expect_valid_gradescope(const json& r) {
  ASSERT_TRUE(r.is_object());
  for (const char* key : {"score", "max_score", "execution_time", "output", "tests"}) EXPECT_TRUE(r.contains(key)) << key;
  for (const auto& t : r["tests"]) {
    for (const char* key : {"name", "number", "score", "max_score", "status", "output", "visibility"})
      EXPECT_TRUE(t.contains(key)) << key << " in " << t.dump();
    EXPECT_TRUE(t["status"] == "passed" || t["status"] == "failed");
    EXPECT_LE(t["score"].get<double>(), t["max_score"].get<double>());
  }
}

inline fs::path copy_solution(const TempDir& dir, const std::string& assignment, const std::string& name) {
  const fs::path to = dir / name;
  fs::create_directories(to);
  for (const auto& e : fs::directory_iterator(fs::path(kAssignments) / assignment / "solution"))
    fs::copy_file(e.path(), to / e.path().filename());
  return to;
}

// The integrators solution with `find` (which must be in it) replaced by `replacement`, and
// `includes` before the file: a submission with one mistake, or one that misbehaves there. Empty
// (and a failure) if the solution has no `find`.
inline fs::path integrators_solution_with(const TempDir& dir, const std::string& name, const std::string& find,
                                          const std::string& replacement, const std::string& includes = "") {
  const fs::path submission = copy_solution(dir, "integrators", name);
  std::string source = read_file(submission / "integrators.cpp");
  const size_t at = source.find(find);
  if (at == std::string::npos) {
    ADD_FAILURE() << "the integrators solution has no " << find;
    return {};
  }
  source.replace(at, find.size(), replacement);
  write_file(submission / "integrators.cpp", includes + source);
  return submission;
}

// The same with `line` put first in its euler_step.
inline fs::path solution_with_euler_step_starting(const TempDir& dir, const std::string& name, const std::string& line,
                                                  const std::string& includes = "") {
  const std::string anchor = "void euler_step(const MechanicalSystem& s, double t, double h, VectorInOut x, VectorInOut v) {\n";
  return integrators_solution_with(dir, name, anchor, anchor + "  " + line + "\n", includes);
}

// A copy of the integrators assignment whose public tests are `tests` (each worth 1 point, visible)
// and which has no hidden tests.
inline fs::path integrators_with_tests(const TempDir& dir, const std::string& name, const nlohmann::json& tests) {
  const fs::path assignment = dir / name;
  fs::copy(fs::path(kAssignments) / "integrators", assignment, fs::copy_options::recursive);
  fs::remove_all(assignment / "hidden");
  nlohmann::json rubric = nlohmann::json::array();
  for (const auto& t : tests) rubric.push_back({{"name", t["name"]}, {"points", 1}, {"visibility", "visible"}});
  write_file(assignment / "tests/public.json", nlohmann::json{{"tests", tests}}.dump(2));
  write_file(assignment / "rubric.json", nlohmann::json{{"tests", rubric}}.dump(2));
  return assignment;
}

inline std::string hidden(const std::string& assignment) { return (fs::path(kAssignments) / assignment / "hidden").string(); }

// Whether no grader holds sandbox user `uid` now (its lock, as SandboxUser takes it, is free).
inline bool sandbox_user_free(long uid) {
  const std::string file = "/run/motus-grade-users/" + std::to_string(uid) + ".lock";
  const int fd = ::open(file.c_str(), O_RDWR | O_CLOEXEC);
  if (fd < 0) return true;  // (never taken on this machine)
  const bool free = ::flock(fd, LOCK_EX | LOCK_NB) == 0;
  ::close(fd);  // (and the lock with it)
  return free;
}

// Processes of the sandbox users (61000 and up) that are still running (zombies excepted), of
// users no grader holds: another grading on the machine at the same time (a second checkout's
// tests) keeps its own user's processes, and they are not this test's leftovers.
inline std::vector<std::string> sandbox_processes_left() {
  std::vector<std::string> left;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename().string();
    if (!std::all_of(pid.begin(), pid.end(), ::isdigit)) continue;
    const std::string status = read_file(entry.path() / "status");
    const auto uid_at = status.find("\nUid:");
    if (uid_at == std::string::npos) continue;
    const long uid = std::strtol(status.c_str() + uid_at + 5, nullptr, 10);
    const bool zombie = status.find("State:\tZ") != std::string::npos;
    if (uid >= 61000 && uid < 61100 && !zombie && sandbox_user_free(uid))
      left.push_back(pid + " " + read_file(entry.path() / "comm"));
  }
  return left;
}

}  // namespace motus_test
