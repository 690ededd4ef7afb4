#include "plugin_loading.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "cli_common.hpp"

namespace motus::cli {

PluginSet& plugins() {
  static PluginSet set;
  return set;
}

void add_plugin_option(CLI::App* command, std::vector<std::string>& files) {
  command->add_option("--plugin", files,
                      "Load a plug-in (FILE.so, a student's code): its integrators as PLUGIN:NAME, its collision "
                      "response or constraint projection in place of motus's (repeatable; assignments/README.md)")
      ->type_name("FILE.so");
}

namespace {
std::FILE* kept_data_output = nullptr;

bool g_watch_plugin_exits = false;
bool g_exit_handler_registered = false;
volatile bool g_main_returning = false;
char g_exit_line[1024] = {};  // written by the handler (no allocation there)

void on_exit_without_main() {
  if (g_main_returning) return;
  std::fflush(stdout);
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, g_exit_line, std::strlen(g_exit_line));
  ::_exit(kExitFailure);
}
}  // namespace

void watch_plugin_exits(bool watch) { g_watch_plugin_exits = watch; }
void main_is_returning() { g_main_returning = true; }

std::FILE* data_output() { return kept_data_output ? kept_data_output : stdout; }

void QuietStandardOutput::begin() {
  if (saved_ >= 0) return;
  std::fflush(stdout);  // what was printed before belongs to the run reported
  const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
  if (null < 0) return;  // (then the prints come once per run, as before)
  saved_ = ::fcntl(STDOUT_FILENO, F_DUPFD_CLOEXEC, 3);
  if (saved_ >= 0 && ::dup2(null, STDOUT_FILENO) < 0) {
    ::close(saved_);
    saved_ = -1;
  }
  ::close(null);
}

void QuietStandardOutput::end() {
  if (saved_ < 0) return;
  std::fflush(stdout);  // the quiet runs' prints, still in the buffer, go where they were sent
  ::dup2(saved_, STDOUT_FILENO);
  ::close(saved_);
  saved_ = -1;
}

std::FILE* keep_data_apart_from_standard_output() {
  if (kept_data_output) return kept_data_output;
  std::fflush(stdout);
  const int data = ::dup(STDOUT_FILENO);
  std::FILE* kept = data < 0 ? nullptr : ::fdopen(data, "w");
  if (!kept || ::dup2(STDERR_FILENO, STDOUT_FILENO) < 0)
    throw std::runtime_error(std::string("standard output could not be kept apart from the plug-in's (") +
                             std::strerror(errno) + ")");
  // What the plug-in prints goes out as it is printed, as standard error's own does: held in a
  // buffer (standard output to a pipe or file is), a student's printf just before a crash was lost
  // with the process, the one time they print to find out where it went wrong.
  std::setvbuf(stdout, nullptr, _IONBF, 0);
  return kept_data_output = kept;
}

void load_plugins(const std::vector<std::string>& files, bool data_on_standard_output) {
  // Before the plug-in's code runs at all (its constructors run as it loads).
  if (!files.empty() && data_on_standard_output) keep_data_apart_from_standard_output();
  if (!files.empty() && g_watch_plugin_exits) {
    std::string names;
    for (const auto& f : files) names += (names.empty() ? "" : ", ") + f;
    const std::string line = "motus: the run did not finish: code in the plug-in " + one_line(names, 600) +
                             " called exit() (motus never does); what it was writing may be left under a "
                             ".NAME.partial-XXXXXX name\n";
    std::snprintf(g_exit_line, sizeof g_exit_line, "%s", line.c_str());
    if (!g_exit_handler_registered) g_exit_handler_registered = std::atexit(on_exit_without_main) == 0;
  }
  try {
    for (const auto& file : files) {
      report_crashes_while_loading(file);
      plugins().load(file);
    }
  } catch (const PluginError& e) {
    throw InputError(e.what());
  }
  report_plugin_crashes(plugins());
}

}  // namespace motus::cli
