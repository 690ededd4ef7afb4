#include "gradescope_package.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli_common.hpp"
#include "locations.hpp"
#include "output_files.hpp"
#include "motus/grade/copy_files.hpp"
#include "motus/grade/grader.hpp"
#include "motus/process/run_program.hpp"

namespace fs = std::filesystem;

namespace motus::cli {
namespace {

// What of motus's source tree it takes to build `motus` on Gradescope's machine: every folder
// the top CMakeLists.txt adds but the tests and the benchmarks (which setup.sh does not build),
// the scenes and examples motus reads, and the package list. (A test configures the zip's copy.)
const char* const kSourceParts[] = {"CMakeLists.txt", "cmake",       "engine",     "expressions", "scene",
                                    "process",        "plot",        "compare",    "precision",   "render",
                                    "plugin",         "grade",       "cli",        "assignments", "scenes",
                                    "examples",       "debian-packages.txt"};

void write_script(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.flush();
  if (!out) throw std::runtime_error(path.string() + ": cannot be written");
  out.close();
  fs::permissions(path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec | fs::perms::others_read |
                            fs::perms::others_exec);
}

// An assignment's reference solution and hidden tests: motus's own tests build and run them,
// the autograder needs neither (it gets the hidden tests it grades with from --hidden).
void leave_out_answers(const fs::path& assignment) {
  for (const char* answers : {"solution", "hidden"}) fs::remove_all(assignment / answers);
}

// The --hidden folder, wherever it lies inside the assignment's folder (under a name of its own,
// "tests-2025-hidden", or reached by a link): it goes into the zip once, as hidden/, which
// run_autograder makes root's only. (It went in twice, the second copy readable by all.)
void leave_out_hidden(const fs::path& assignment, const fs::path& hidden, const fs::path& copy) {
  std::error_code error;
  const fs::path target = fs::canonical(hidden, error);
  if (error) return;
  std::vector<fs::path> inside;  // relative to the assignment's folder
  for (auto it = fs::recursive_directory_iterator(assignment, error); !error && it != fs::recursive_directory_iterator();
       it.increment(error)) {
    std::error_code ignored;
    if (!it->is_directory(ignored)) continue;
    if (fs::canonical(it->path(), ignored) == target) {
      inside.push_back(it->path().lexically_relative(assignment));
      it.disable_recursion_pending();
    }
  }
  for (const auto& relative : inside) fs::remove_all(copy / relative, error);
}

// zip -q -r -X ZIP . in `folder`, started directly (no shell). zip adds ".zip" to a name without an
// extension: then it writes ZIP.zip, moved to ZIP (--out autograder wrote autograder.zip, and the move
// of "autograder" into place failed after the work). `shown`: the user's name for the zip, for messages.
// A temporary folder, removed with what it holds however the scope is left.
struct RemovedAtEnd {
  fs::path path;
  ~RemovedAtEnd() {
    std::error_code ignored;
    fs::remove_all(path, ignored);
  }
};

void zip_folder(const fs::path& folder, const fs::path& zip, const std::string& shown) {
  const std::string program = process::find_program("zip");
  if (program.empty()) throw InputError("--package: the program zip was not found on PATH (apt-get install zip)");
  const fs::path made = zip.has_extension() ? zip : fs::path(zip.string() + ".zip");
  // zip's own words go to a log outside the zipped folder, and its last line into motus's one
  // line: on a full disk it printed two lines of its own before motus's.
  const fs::path logs(grade::make_temporary_folder("", "motus-zip-"));
  const RemovedAtEnd remove_logs{logs};
  const process::Outcome run =
      process::run_program({program, "-q", "-r", "-X", made.string(), "."}, folder.string(), (logs / "zip.log").string());
  if (!run.started)  // (it said "exit status -1", of a zip that never ran)
    throw std::runtime_error(shown + ": " + run.not_started("zip", program));
  if (!run.ok()) {
    std::ifstream log(logs / "zip.log");
    std::string line, last;
    while (std::getline(log, line))
      if (!line.empty()) last = line;
    throw std::runtime_error(shown + ": zip failed to write it (" +
                             (run.signal ? "signal " + std::to_string(run.signal) : "exit status " + std::to_string(run.status)) +
                             (run.status == 14 ? ": a write failed; a full disk?" : "") + (last.empty() ? "" : "; zip said: " + last) + ")");
  }
  if (made != zip) {
    std::error_code error;
    fs::rename(made, zip, error);
    if (error) throw std::runtime_error(shown + ": could not be written (" + error.message() + ")");
  }
}

std::string quoted(const std::string& s) {  // for a shell script's double quotes
  std::string q;
  for (char c : s) {
    if (c == '"' || c == '\\' || c == '$' || c == '`') q += '\\';
    q += c;
  }
  return q;
}

}  // namespace

int write_gradescope_package(const std::string& assignment_folder, const std::string& assignment_name,
                             const std::optional<std::string>& hidden, const std::string& zip, bool no_sandbox,
                             double time_limit, long memory_limit, bool overwrite) {
  check_can_replace(zip, overwrite);
  const std::string source = source_directory();
  if (source.empty()) throw InputError("--package: needs the source tree motus was built from (it goes into the zip)");
  const fs::path staging(grade::make_temporary_folder("", "motus-package-"));
  const RemovedAtEnd cleanup{staging};

  const fs::path motus = staging / "motus";
  fs::create_directories(motus);
  for (const char* part : kSourceParts) {
    const fs::path from = fs::path(source) / part;
    if (fs::exists(from)) grade::copy_tree_told(from.string(), (motus / part).string());
  }
  // The assignment graded (it may live outside the source tree) and its hidden tests. No
  // assignment's solution or hidden tests go in with the sources: a student's code may run in
  // this image without the sandbox (--no-sandbox), and what it could read it could print.
  if (fs::is_directory(motus / "assignments"))
    for (const auto& entry : fs::directory_iterator(motus / "assignments"))
      if (entry.is_directory()) leave_out_answers(entry.path());
  grade::copy_tree_told(assignment_folder, (staging / "assignment").string());
  leave_out_answers(staging / "assignment");
  if (hidden) {
    grade::copy_tree_told(*hidden, (staging / "hidden").string());
    leave_out_hidden(assignment_folder, *hidden, staging / "assignment");
  }

  // The packages of debian-packages.txt (motus's one list, read whole by the README's commands) that
  // only the tests, the benchmarks and the fuzzers need, left out of the autograder's image: the
  // motus target configured with BUILD_TESTING and MOTUS_BUILD_BENCH off finds none of them (the
  // fuzzers are a project of their own, fuzz/, which the zip does not hold), and grading runs none.
  write_script(staging / "setup.sh", R"SH(#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image: the Debian
# packages motus needs, then motus itself (the tests and benchmarks are not built).
set -euo pipefail
cd "$(dirname "$0")"
# motus's package list is Debian 12's (bookworm), and this script has been tried on Debian 12
# only. Gradescope's base images are Ubuntu: a package's name or version may differ there, and
# apt-get or cmake below then stops, naming what it could not find.
os="$(. /etc/os-release 2>/dev/null && echo "${ID:-}-${VERSION_ID:-}" || true)"
os_name="$(. /etc/os-release 2>/dev/null && echo "${PRETTY_NAME:-}" || true)"
if [ "$os" != "debian-12" ]; then
  echo "setup.sh: warning: this image is ${os_name:-not named in /etc/os-release}, not Debian 12 (bookworm), the only" \
       "one this script was tried on: motus/debian-packages.txt names Debian 12's packages, and here a name or a" \
       "version may differ (apt-get or cmake below then stops, naming it)" >&2
fi
apt-get update
# Every package of motus/debian-packages.txt but those only motus's tests, benchmarks and fuzzers
# need (none of them is found when the motus target is configured as below, nor used to grade).
grep -vxF -e chromium -e clang -e libfuzzer-14-dev -e libclang-rt-14-dev -e libgtest-dev -e libgmock-dev \
  -e libbenchmark-dev -e python3-jsonschema motus/debian-packages.txt |
  DEBIAN_FRONTEND=noninteractive xargs apt-get install -y --no-install-recommends
cmake -S motus -B motus/build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF -DMOTUS_BUILD_BENCH=OFF
cmake --build motus/build -j"$(nproc)" --target motus
)SH");
  write_script(staging / "run_autograder",
               fmt::format(R"SH(#!/usr/bin/env bash
# Gradescope runs this for every submission: grade /autograder/submission into
# /autograder/results/results.json ($AUTOGRADER_ROOT moves /autograder, $MOTUS_BINARY the motus
# that grades — for a test of this zip). Written by motus grade --package gradescope.
set -uo pipefail
ROOT="${{AUTOGRADER_ROOT:-/autograder}}"
SOURCE="$ROOT/source"
MOTUS="${{MOTUS_BINARY:-$SOURCE/motus/build/motus}}"
mkdir -p "$ROOT/results"
# The hidden tests for root (the grader) only: with --no-sandbox the student's code runs as an
# unprivileged user of this machine, and must not read them.
[ -d "$SOURCE/hidden" ] && chmod -R go-rwx "$SOURCE/hidden"
exec "$MOTUS" grade "$SOURCE/assignment" "$ROOT/submission" {}--results "$ROOT/results/results.json" --overwrite \
  --time-limit {} --memory-limit {}{}
)SH",
                           hidden ? "--hidden \"$SOURCE/hidden\" " : "", time_limit, memory_limit,
                           no_sandbox ? " --no-sandbox" : ""));
  write_script(staging / "README.txt",
               fmt::format("The Gradescope autograder for the motus assignment \"{}\", written by `motus grade {} "
                           "--package gradescope`.\nUpload this zip as the autograder; setup.sh builds motus, "
                           "run_autograder grades each submission.\n",
                           quoted(assignment_name), quoted(assignment_name)));
  PartialFile partial(zip);  // (zip adds to an archive that is there: it writes a new one in a folder of its own)
  zip_folder(staging, fs::absolute(partial.path()), zip);
  partial.complete(overwrite);
  fmt::print("autograder  {} (setup.sh, run_autograder; motus's sources, the assignment{})\n", zip,
             hidden ? " and its hidden tests" : "");
  return 0;
}

}  // namespace motus::cli
