#pragma once
// Running the built `motus` binary as a user would, for the command-line tests: a fresh
// temporary folder per test, the command's exit status, standard output and standard
// error. MOTUS_BINARY and MOTUS_SCENES_DIR come from tests/CMakeLists.txt.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
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

private:
  fs::path path_;
};

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'')
      q += "'\\''";
    else
      q += c;
  }
  return q + "'";
}

struct Result {
  int status = -1;
  std::string out, err;
};

// Runs `motus ARGS...` with standard output and error captured in files of `dir`.
// `environment` ("" or "NAME=value ...") is put before the command.
Result run_motus(const TempDir& dir, const std::vector<std::string>& args, const std::string& environment = "") {
  std::string command = environment;
  if (!command.empty()) command += ' ';
  command += shell_quote(kMotus);
  for (const auto& a : args) {
    command += ' ';
    command += shell_quote(a);
  }
  const fs::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  command += " >";
  command += shell_quote(out.string());
  command += " 2>";
  command += shell_quote(err.string());
  command += " </dev/null";
  const int raw = std::system(command.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  return r;
}

long count_lines(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }

}  // namespace motus_test
