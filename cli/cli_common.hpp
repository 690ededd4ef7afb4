#pragma once
// What the `motus` subcommands share: finding scenes, the exit codes, and the one-line
// error for input that cannot be used.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "motus/method.hpp"
#include "motus/plugin/plugin_set.hpp"
#include "motus/scene.hpp"

namespace motus {
class Simulation;
class World;
}

namespace motus::cli {

// Exit codes: 0 done; 1 the run itself failed; 2 bad input (scene, option or file).
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

// A message for the user on standard error, as fmt::print(stderr, …) prints it, but never
// throwing. With standard error closed or full (2>&-, 2>/dev/full) fmt::print throws, and the
// handler that then prints the error threw again: motus aborted (exit 134) instead of exiting 1
// or 2. What cannot be written is lost; the exit status still says what happened.
template <typename... Args>
void tell(fmt::format_string<Args...> format, Args&&... args) noexcept {
  try {
    const std::string text = fmt::format(format, std::forward<Args>(args)...);
    if (std::fwrite(text.data(), 1, text.size(), stderr) != text.size()) std::clearerr(stderr);
  } catch (...) {
  }
}

// Bad input that is not inside a scene file (an option, an output path): exit 2.
class InputError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// This executable, and the folder it is in (from /proc/self/exe).
std::string executable_path();
std::string executable_directory();
// The folder of shipped assignments: $MOTUS_ASSIGNMENTS; else, for an installed motus,
// PREFIX/share/motus/assignments; else the source tree's assignments/.
std::string assignments_directory();
// Where the headers a student's plug-in is compiled against are: `which` is "student",
// "plugin" or "external" (…/motus/WHICH), installed beside this motus or in the source tree.
std::string student_api_directory(const std::string& which);
// The source tree motus was built from ("" when it is gone).
std::string source_directory();
// The folder of shipped scenes: $MOTUS_SCENES; else, for an installed motus, the scenes
// installed beside it (PREFIX/share/motus/scenes); else the source tree's scenes/.
std::string scenes_directory();
// A scene argument as given: a path to a file, or the name of a shipped scene
// ("spring" or "spring.json"). A name that is neither is returned as it is (the loader says "no
// such file"), unless it is a slip away from a shipped scene's: then InputError says which.
std::string resolve_scene_path(const std::string& argument);
// As resolve_scene_path, without the guess.
std::string find_scene_path(const std::string& argument);
// ", did you mean spring?" for a name a slip away from a shipped scene's ("sprng"), else "".
std::string shipped_scene_guess(const std::string& name);
// Every shipped scene file, sorted.
std::vector<std::string> shipped_scenes();

// A comma-separated list option (--engines motus,box2d; repeatable, the lists joined).
// CLI11's own splitting drops empty items, so "motus,,box2d" would quietly run two engines:
// here an empty item, like a value that is not a T, is a parse error (one line, exit 2).
template <class T>
CLI::Option* add_list_option(CLI::App* command, const std::string& name, std::vector<T>& values,
                             const std::string& help) {
  auto* option = command->add_option_function<std::vector<std::string>>(
      name,
      [&values, name](const std::vector<std::string>& given) {
        values.clear();
        for (const std::string& list : given) {
          size_t from = 0;
          for (;;) {
            const size_t comma = std::min(list.find(',', from), list.size());
            const std::string item = list.substr(from, comma - from);
            if (item.empty()) throw CLI::ValidationError(name, "an empty item in \"" + list + "\"");
            T value{};
            if (!CLI::detail::lexical_cast(item, value))
              throw CLI::ValidationError(name, "\"" + item + "\" is not a " + std::string(CLI::detail::type_name<T>()));
            values.push_back(std::move(value));
            if (comma == list.size()) break;
            from = comma + 1;
          }
        }
      },
      help);
  option->type_name(std::string(CLI::detail::type_name<T>()) + ",...")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  return option;
}

// The plug-ins of this process (--plugin FILE.so, repeatable on run, render, compare,
// bench precision and list), loaded by load_plugins.
PluginSet& plugins();
// What to suspect when a run's state stops being finite: what the scene's system says made it so
// (an equation that gave a NaN: FirstOrderSystem::why_not_finite); else a plug-in's integrator
// (`method`) or its collision response or constraint projection when one ran, named with its file;
// otherwise the step, too large for the integrator. One clause, for "the state was no longer
// finite by t = …". (`smaller_step`: how this command takes a smaller step; render has no --dt.)
std::string non_finite_suspect(const Simulation& sim, const Method& method, const std::string& smaller_step = "a smaller --dt");
// Adds --plugin to a subcommand.
void add_plugin_option(CLI::App* command, std::vector<std::string>& files);

// Where run and compare write data that a program reads (--json, run's --trajectory -): standard
// output, unless a plug-in was loaded while it carried such data. A plug-in's code runs in this
// process and shares descriptor 1, so its printf or std::cout would land between a CSV's rows or
// inside the JSON object; load_plugins(files, true) then points descriptor 1 at standard error
// for everyone, the plug-in's prints and motus's own messages alike, and the data go to a copy of
// what standard output was. (serve keeps its answers apart the same way, before the sandbox's
// filter is installed: keep_data_apart_from_standard_output.)
std::FILE* data_output();
// Makes data_output() a copy of descriptor 1 and points descriptor 1 at standard error (once; later
// calls return the same copy). Throws std::runtime_error when it cannot.
std::FILE* keep_data_apart_from_standard_output();

// While begun, descriptor 1 writes to /dev/null: the timing runs after the one reported, so that
// what a plug-in's code prints on standard output comes once, with the run it belongs to, not
// once more per timing run. (Standard error, the progress bar's, is left alone.)
class QuietStandardOutput {
public:
  QuietStandardOutput() = default;
  QuietStandardOutput(const QuietStandardOutput&) = delete;
  QuietStandardOutput& operator=(const QuietStandardOutput&) = delete;
  ~QuietStandardOutput() { end(); }
  void begin();
  void end();

private:
  int saved_ = -1;  // descriptor 1 as it was
};
// A plug-in's code that calls exit() ends motus with the status it gives: exit(0) read as a run
// that went well and said nothing, its folders half-written. motus itself never calls exit, so
// once a plug-in is loaded (when watch_plugin_exits(true) was called: not in serve, whose grader
// reports it) an atexit handler makes any exit that main's return did not make one line naming
// the plug-ins, and exit 1. main calls main_is_returning() as it returns.
void watch_plugin_exits(bool watch);
void main_is_returning();

// Loads them, in order, and from then on reports a crash in their code; a file that is not
// a usable plug-in is an InputError (one line, exit 2). `data_on_standard_output`: the command
// writes data for a program there (see data_output).
void load_plugins(const std::vector<std::string>& files, bool data_on_standard_output = false);

// The integrator a subcommand runs: --integrator when given (a built-in, or PLUGIN:NAME from
// a loaded plug-in), else the scene's; one line naming the file when it is unknown, or
// symplectic on a first-order scene.
Method method_for(const std::string& path, const SceneDescription& scene, const std::optional<std::string>& requested);
// {"euler", "midpoint", ..., "student:euler", ...}: the built-in integrators and the plug-ins', for messages.
std::vector<std::string> known_integrators();
// Names joined by ", " in at most `budget` bytes, each whole: those that do not fit are counted at
// the end ("euler, midpoint, …and 12 more"). (main prints a message as one line of at most 400
// bytes, cut in its middle: a long list of integrators was cut inside a name, "symplectic-eule…verlet".)
std::string whole_names(const std::vector<std::string>& names, size_t budget);
// The room a list has in a message that is `before` it and `after` it: what keeps the whole within
// main's one line of 400 bytes, and at least 120 bytes (a path or a name that takes the rest is
// what main then cuts, in the middle, and the list at the end is kept).
size_t room_for_list(const std::string& before, const std::string& after);
// What a loaded plug-in brings, in words: "8 integrators (student:euler, student:midpoint, …)",
// "collision rules", "a constraint projection", joined by "and"; "nothing" when it brings none.
std::string what_plugin_brings(const LoadedPlugin& plugin);
// One line for standard error ("note: the plug-in cloth.so brings a constraint projection, and spring
// has no sticks or pins: it is not used in this run"), for each loaded plug-in of which a run uses
// nothing: not its integrator (`method` is not one of its), nor its collision rules or its
// projection (the scene's `world` runs no such pass; null for a first-order system). Nothing when
// no plug-in is loaded or every one is used. `scene_name` names the scene in the note.
std::vector<std::string> unused_plugin_notes(const std::string& scene_name, const Method& method, const World* world);

// What the scene's time is counted in, for people: "s", or "years" for World2 (the system
// catalog's time_unit).
std::string time_unit_of(const SceneDescription& scene);

// The 1-minute load average: the first number of /proc/loadavg — or of the file MOTUS_LOADAVG
// names, the tests' way to make the machine look busy or idle; NaN when it cannot be read.
double load_average();
// The cores the machine has online (as the grader counts them), or 0 when it does not say.
long online_cores();

// A name (a scene's, say) made safe as one file name: letters, digits, '.', '-' and '_' are
// kept, anything else becomes '_', no leading dot, at most 64 characters; "scene" if nothing is
// left. A scene named "../victim" writes "victim", inside the folder it was given.
std::string safe_file_name(const std::string& name);

// An error message as one line of at most `limit` bytes (shortened in the middle, bytes that are
// not UTF-8 as '?'): messages echo what the user gave, which may be long, have line breaks or be a
// file name of raw bytes.
std::string one_line(const std::string& text, size_t limit = 400);

// The most fixed steps a run may take: beyond this a step count is not a number to count in
// (and t0 + i·dt is no longer exact in double precision).
constexpr double kMaxSteps = 1e15;
// The number of fixed steps of dt that `duration` takes; InputError naming `what` when it is
// not a number of steps one could count.
long checked_step_count(double duration, double dt, const std::string& what);
// Refuses a mechanical scene so far from the origin that its positions cannot take its moves at the
// step `dt` a command runs (exit 2), naming the field that puts its bodies there: at 1e17 m doubles
// are 16 m apart, and a ball at 1 m/s with dt = 0.01 never moved, exit 0. The rule, and the field
// named (a body's position, a generator's origin or spacing, a wall's offset or corner), are
// positions_too_coarse's (motus/scene_file/scene_file.hpp): the moves, a body's speed times dt at the
// start or after the scene's duration under the forces at the start, must be at least a thousand times
// the positions' spacing where the bodies are.
void check_position_resolution(const SceneDescription& scene, double dt, const std::string& path);
// Refuses a run whose times cannot be told apart at its step (exit 2), naming start_what when
// start_time is what takes the run far from 0, else step_what (dt, the duration or the option).
void check_time_resolution(double start_time, double duration, double dt, const std::string& start_what,
                           const std::string& step_what);

// Where a module of the `motus` command may be (motus-draw.so, motus-peers.so, motus-expressions.so): at $ENV_VAR when
// that is set and not empty (and only there), else next to the executable (the build tree), else
// at `installed`, relative to the executable (where `cmake --install` puts it).
std::vector<std::string> module_candidates(const char* env_var, const std::string& name, const std::string& installed);

// The folder of a run the user gave no --out for: runs/KIND-SCENE-YYYYmmdd-HHMMSS (KIND: compare,
// precision, stress). Not made here: a PartialFolder made with `numbered` takes it, or the first of
// NAME-2, NAME-3, … free when the run is whole (two runs of a scene started in the same second
// both get a folder).
std::string default_run_folder(const std::string& kind, const std::string& scene_name);

// "out/" names the folder "out": its parent is the parent of out, not out itself (which
// parent_path() of "out/" would give, and a report would be made inside the folder it is to become).
std::filesystem::path without_trailing_separators(const std::string& path);

// The folders above a path that are not there yet (`folder` and its parents up to the first that
// exists), deepest first: the ones a create_directories(folder) will make, and that a run which fails
// or is stopped removes again (remove_if_empty) — an interrupted run said "nothing half-written was
// left behind" and left the empty folders of its --out's path.
std::vector<std::string> folders_not_there_yet(const std::string& folder);
// Why `folder` could not be made, for "cannot be created (...)": a link to nothing on its way named
// as such, or else `error`'s own words.
std::string why_not_created(const std::string& folder, const std::error_code& error);
// Removes each of `folders` (deepest first) while it is empty or already gone; stops at the first that
// is not (nothing with anything in it is ever removed).
void remove_if_empty(const std::vector<std::string>& folders);

// A message with every temporary folder or file this process has made (PartialFolder, PartialFile,
// render's folder) said as what it was to become: a failure removes the temporary one, and a
// message naming it named a path gone. main's one-line errors go through it, so that
// "a/.r.partial-Xb3/summary.json: could not be written" reads "a/r/summary.json: …". One that is
// kept (a name taken meanwhile: the message says where the work is) is said as it is.
void say_as_final(const std::string& partial, const std::string& final);
void say_as_it_is(const std::string& partial);
std::string named_as_final(std::string message);

// A folder written under a temporary name and renamed to `final_path` only when complete()
// is called; otherwise the destructor removes it and everything in it. Throws InputError
// when it cannot be made.
class PartialFolder {
public:
  // numbered: final_path is a default name (default_run_folder), and when it is taken the folder
  // goes to final_path-2, -3, … instead of failing.
  explicit PartialFolder(const std::string& final_path, bool numbered = false);
  ~PartialFolder();
  PartialFolder(const PartialFolder&) = delete;
  PartialFolder& operator=(const PartialFolder&) = delete;
  const std::string& path() const { return partial_; }
  // Where the folder is now. Throws std::runtime_error when the rename fails (e.g. a name the user
  // gave was taken meanwhile: the work is kept where the message says).
  const std::string& complete();

private:
  std::string final_, partial_;
  std::vector<std::string> made_parents_;  // the folders above it that it made, deepest first
  bool numbered_;
  bool done_ = false;
};

// A file written whole or not at all: written as NAME inside a new folder of its own beside it
// (.NAME.partial-XXXXXX, made by mkdtemp, so that nothing already there is truncated and no link
// is followed), and moved to `final_path` by complete(): over a file there only with
// `overwrite`; without it, a file that appeared there meanwhile is left as it is (an error that
// says where the work was kept). Otherwise the destructor removes the folder and the file.
// Throws InputError when the folder cannot be made.
class PartialFile {
public:
  explicit PartialFile(const std::string& final_path);
  ~PartialFile();
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;
  const std::string& path() const { return file_; }  // where to write it
  void complete(bool overwrite);                     // throws std::runtime_error naming final_path

private:
  std::string final_, folder_, file_;
  bool done_ = false;
};

// Refuses to overwrite an existing file unless asked to (nothing the user wrote is
// lost without being asked), and a folder even then. For a file written in place: a FIFO or a
// device (/dev/full) is written to as it is.
void check_can_write(const std::string& path, bool overwrite);
// Writes `text` to `path` whole or not at all (through a PartialFile), over a file there only with
// `overwrite`; a FIFO or a device is written as it is. Fails with one line naming the path.
void write_whole_file(const std::string& path, const std::string& text, bool overwrite);
// Whether `path` is written as it is rather than through a PartialFile: a FIFO or a device.
bool written_in_place(const std::string& path);
// The temporary name of a file or folder named `name`, with mkdtemp's XXXXXX: .NAME.partial-XXXXXX,
// or .partial-XXXXXX when that would be longer than a file name may be.
std::string partial_name_for(const std::string& name);
// The folder a PartialFile for `path` is written in: partial_name_for its name, beside it.
std::string partial_folder_pattern_for(const std::string& path);
// The same for a file written whole under another name and then renamed over `path`: the
// rename would put a regular file where a device or a FIFO was, so only a regular file (or a
// link, which the rename replaces and does not follow) may be overwritten.
void check_can_replace(const std::string& path, bool overwrite);

// What is at `path` (links followed), for an input the user named: a path that cannot be looked at
// (a loop of links, a name too long, a folder not to be entered) is bad input, one line naming it
// and `option` ("--batch"; "" for an argument), where std::filesystem's throwing calls made it
// "the run failed: filesystem error: status: …", exit 1. Nothing there is a status of not_found.
std::filesystem::file_status looked_at(const std::string& path, const std::string& option = "");

// Whether something is at `path`, a folder an output would go to. A path that cannot be looked
// at (a name too long, a loop of links, a folder not to be entered) is bad input naming it.
bool output_exists(const std::string& path);

// For the options that name a file or folder to write: an empty one is refused, not taken for
// "not given" (which would write nothing, or somewhere else, and say nothing).
// A folder to be made: not empty, and not ending in "." or ".." ("new/." ran the whole job, then
// failed to move the finished folder into place and left it under a hidden name).
CLI::Validator folder_path(const std::string& what = "folder");
const CLI::Validator& non_empty_path();

// For the options that count (steps, repeats, samples, levels): a whole number from `low` to `high`,
// as written. CLI11's Range said "Value 1e4 not in range 100 to 10000000" of a number inside the
// range that is not whole; this says what is wrong: "must be a whole number from 100 to 10000000
// (got 1e4)". Added with ->transform(): it passes the number on in plain decimal, as it read it
// (CLI11 reads a leading 0 as octal: --steps 010 ran 8 steps).
CLI::Validator whole_number_in(long low, long high);
// For a whole-number option checked after parsing (--memory-limit, --jobs): a leading 0 read as
// decimal, not octal; anything else left for CLI11's conversion to refuse. With ->transform().
CLI::Validator read_as_decimal();
// For a number option with no default (--dt, --duration, --rtol, --atol), with ->transform(): the
// blanks around it dropped, and an empty value refused. CLI11 reads "" into an empty
// std::optional, and `--dt ''` ran at the scene's dt, exit 0.
CLI::Validator a_number();

}  // namespace motus::cli
