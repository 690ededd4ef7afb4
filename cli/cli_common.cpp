#include "cli_common.hpp"

#include "motus/systems/system_catalog.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <stdio.h>  // renameat2, RENAME_NOREPLACE
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <optional>
#include <fstream>

#include <fmt/format.h>

#include <ctime>

#include "motus/plot/write_failure.hpp"
#include "motus/scene_file/printable_text.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/scene_file/spelling.hpp"
#include "motus/simulation.hpp"

namespace fs = std::filesystem;

namespace motus::cli {

std::string executable_path() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  return error ? std::string("motus") : self.string();
}

std::string executable_directory() { return fs::path(executable_path()).parent_path().string(); }

std::string assignments_directory() {
  if (const char* env = std::getenv("MOTUS_ASSIGNMENTS"); env && *env) return env;
  const fs::path installed = (fs::path(executable_directory()) / MOTUS_SCENES_INSTALLED / ".." / "assignments").lexically_normal();
  std::error_code error;
  if (fs::is_directory(installed, error)) return installed.string();
  return (fs::path(MOTUS_SOURCE_DIR) / "assignments").string();
}

std::string student_api_directory(const std::string& which) {
  const fs::path installed =
      (fs::path(executable_directory()) / MOTUS_INCLUDE_INSTALLED / "motus" / which).lexically_normal();
  std::error_code error;
  if (fs::is_directory(installed, error)) return installed.string();
  const fs::path source(MOTUS_SOURCE_DIR);
  return (which == "external" ? source / "engine/motus/external" : source / "plugin/motus" / which).string();
}

std::string source_directory() {
  std::error_code error;
  return fs::is_regular_file(fs::path(MOTUS_SOURCE_DIR) / "CMakeLists.txt", error) ? MOTUS_SOURCE_DIR : "";
}

std::string scenes_directory() {
  if (const char* env = std::getenv("MOTUS_SCENES"); env && *env) return env;
  const fs::path installed = (fs::path(executable_directory()) / MOTUS_SCENES_INSTALLED).lexically_normal();
  std::error_code error;
  if (fs::is_directory(installed, error)) return installed.string();
  return MOTUS_SOURCE_SCENES_DIR;  // set by CMake
}

std::string shipped_scene_guess(const std::string& name) {
  if (name.find('/') != std::string::npos) return "";
  std::error_code error;
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(scenes_directory(), error))
    if (entry.path().extension() == ".json") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  const std::string stem = fs::path(name).extension() == ".json" ? fs::path(name).stem().string() : name;
  return did_you_mean(stem, names);
}

std::string find_scene_path(const std::string& argument) {
  std::error_code error;  // (a link that loops is the loader's to report, in one line)
  const auto status = fs::symlink_status(argument, error);
  const bool plain_name = argument.find('/') == std::string::npos;
  // A folder of the same name as a shipped scene (a student's copy of the cloth starter in ./cloth)
  // is no scene: `motus run cloth` still means the shipped one. ("./cloth" names the folder.)
  const bool folder = fs::is_directory(status);
  if ((fs::exists(status) && !(folder && plain_name)) || (error && error != std::errc::no_such_file_or_directory))
    return argument;
  if (plain_name) {
    fs::path shipped = fs::path(scenes_directory()) / argument;
    if (shipped.extension() != ".json") shipped += ".json";
    if (fs::exists(shipped, error)) return shipped.string();
    // Where it was looked for, when MOTUS_SCENES chose the folder (else the loader's "no such
    // file (motus list shows the scenes)" says it).
    if (const char* env = std::getenv("MOTUS_SCENES"); env && *env)
      throw InputError(argument + ": no such file here, nor " + shipped.filename().string() + " in MOTUS_SCENES=" + env +
                       " (motus list shows the scenes)");
  }
  return argument;  // the loader says "no such file"
}

std::string resolve_scene_path(const std::string& argument) {
  const std::string path = find_scene_path(argument);
  // A shipped scene's name, misspelt ("sprng"): the name it most likely is.
  std::error_code error;
  if (path == argument && !fs::exists(fs::symlink_status(argument, error)))
    if (const std::string guess = shipped_scene_guess(argument); !guess.empty())
      throw InputError(argument + ": no such file, nor a shipped scene of that name" + guess +
                       " (motus list shows the scenes)");
  return path;
}

std::string non_finite_suspect(const Simulation& sim, const Method& method, const std::string& smaller_step) {
  if (const FirstOrderSystem* system = sim.first_order_system())
    if (std::string why = system->why_not_finite(); !why.empty()) return why;
  for (const auto& p : plugins().plugins()) {
    const auto& names = p.integrator_names;
    if (method.is_external() && std::find(names.begin(), names.end(), method.name()) != names.end())
      return "check the plug-in's integrator " + method.name() + " (" + p.file + "), or try " + smaller_step;
  }
  for (const auto& p : plugins().plugins())
    if (p.entry->collisions || p.entry->constraints)
      return "check the plug-in's " + std::string(p.entry->collisions ? "collision response" : "constraint projection") +
             " (" + p.file + "); else the integrator is unstable at this step";
  return "the integrator is unstable at this step; try " + smaller_step + " or another --integrator";
}

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> files;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(scenes_directory(), error))
    if (entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

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

std::vector<std::string> known_integrators() {
  std::vector<std::string> names = integrator_names();
  for (const auto& m : plugins().integrators()) names.push_back(m.name());
  return names;
}

std::string whole_names(const std::vector<std::string>& names, size_t budget) {
  std::string list;
  for (size_t k = 0; k < names.size(); ++k) {
    const std::string next = (list.empty() ? "" : ", ") + names[k];
    // (Room is kept for saying how many follow, should the next one not fit.)
    const size_t after = names.size() - k - 1;
    const size_t more = after ? fmt::format(", …and {} more", after).size() : 0;
    if (list.size() + next.size() + more > budget)
      return list + (list.empty() ? "" : ", ") + fmt::format("…and {} more", names.size() - k);
    list += next;
  }
  return list;
}

size_t room_for_list(const std::string& before, const std::string& after) {
  constexpr size_t line = 400, least = 120;
  const size_t used = before.size() + after.size();
  return used + least > line ? least : line - used;
}

namespace {

std::string joined_with_and(const std::vector<std::string>& items) {
  std::string text;
  for (size_t k = 0; k < items.size(); ++k) text += (k == 0 ? "" : k + 1 == items.size() ? " and " : ", ") + items[k];
  return text;
}

// What a plug-in brings besides integrators (the parts that replace motus's own), in words, or "".
std::string plugin_parts_in_words(const LoadedPlugin& p) {
  std::vector<std::string> parts;
  if (p.entry->collisions) parts.emplace_back("collision rules");
  if (p.entry->constraints) parts.emplace_back("a constraint projection");
  return joined_with_and(parts);
}


// The message for an integrator that is neither built in nor a loaded plug-in's.
std::string unknown_integrator(const std::string& path, const std::string& name) {
  const std::string head = path + ": --integrator: unknown integrator \"" + name + "\"";
  const size_t colon = name.find(':');
  const std::vector<std::string> known = known_integrators();
  auto with_list = [&](const std::string& before, const std::vector<std::string>& names, const std::string& after) {
    return before + whole_names(names, room_for_list(before, after)) + after;
  };
  if (colon == std::string::npos) return with_list(head + did_you_mean(name, known) + " (known: ", known, ")");
  const std::string owner = name.substr(0, colon), own = name.substr(colon + 1);
  if (plugins().empty())
    return with_list(head + did_you_mean(name, known) + " (known: ", known,
                     "); " + owner + ":NAME integrators come from a plug-in, and none is loaded: load its plug-in with "
                                     "--plugin FILE.so");
  const LoadedPlugin* named = nullptr;
  for (const auto& p : plugins().plugins())
    if (p.name == owner) named = &p;
  if (named && named->integrator_names.empty()) {
    // (The course's plug-ins are all "student": the collisions one loaded for student:euler.)
    const std::string parts = plugin_parts_in_words(*named);
    return head + ": the plug-in " + named->file + " brings no integrators" +
           (parts.empty() ? "" : " (it brings " + parts + ")") +
           (owner == "student" ? "; the integrators assignment's plug-in does"
                               : "; load a plug-in that brings them with --plugin FILE.so");
  }
  if (named) {
    // Its own integrators, first and whole: the built-ins' names would crowd them out of the line.
    const std::string builtin = integrator_from_name(own) ? "; motus's own is --integrator " + own : "";
    return with_list(head + did_you_mean(name, named->integrator_names) + " (" + named->file + " brings ",
                     named->integrator_names, ")" + builtin);
  }
  std::vector<std::string> loaded;
  for (const auto& p : plugins().plugins()) loaded.push_back("\"" + p.name + "\" from " + p.file);
  return with_list(head + did_you_mean(name, known) + " (known: ", known,
                   "); no loaded plug-in is named \"" + owner + "\" (loaded: " + joined_with_and(loaded) + ")");
}

}  // namespace

std::string what_plugin_brings(const LoadedPlugin& plugin) {
  std::vector<std::string> brings;
  const auto& names = plugin.integrator_names;
  if (names.size() == 1) brings.push_back("an integrator (" + names.front() + ")");
  else if (names.size() == 2) brings.push_back("2 integrators (" + names[0] + ", " + names[1] + ")");
  else if (names.size() > 2)
    brings.push_back(fmt::format("{} integrators ({}, {}, …)", names.size(), names[0], names[1]));
  if (const std::string parts = plugin_parts_in_words(plugin); !parts.empty()) brings.push_back(parts);
  return brings.empty() ? "nothing" : joined_with_and(brings);
}

std::vector<std::string> unused_plugin_notes(const std::string& scene_name, const Method& method, const World* world) {
  std::vector<std::string> notes;
  for (const auto& p : plugins().plugins()) {
    const auto& names = p.integrator_names;
    const bool integrates = method.is_external() && std::find(names.begin(), names.end(), method.name()) != names.end();
    const bool collides = p.entry->collisions && world && world->has_collisions();
    const bool projects = p.entry->constraints && world && world->has_constraints();
    if (integrates || collides || projects) continue;
    std::vector<std::string> why;
    if (!names.empty())
      why.push_back("this run integrates with " + method.name() + " (--integrator " + p.name + ":NAME runs one of them)");
    if ((p.entry->collisions || p.entry->constraints) && !world)
      why.push_back(scene_name + " is a first-order system, with no bodies");
    if (p.entry->collisions && world)
      why.push_back(world->has_constraints() ? scene_name + " has no collision pass (on verlet its contacts are projected)"
                                             : scene_name + " has no collisions");
    if (p.entry->constraints && world)
      why.push_back(scene_name + " has no sticks or pins" +
                    (world->has_collisions() ? " (its contacts are collided, on " + method.name() +
                                                   "; --integrator verlet projects them)"
                                             : ""));
    notes.push_back("note: the plug-in " + p.file + " brings " + what_plugin_brings(p) +
                    (why.empty() ? "" : ", and " + joined_with_and(why)) + ": it is not used in this run");
  }
  return notes;
}

Method method_for(const std::string& path, const SceneDescription& scene, const std::optional<std::string>& requested) {
  const std::string name = requested.value_or(scene.integrator);
  std::optional<Method> method;
  if (const auto builtin = integrator_from_name(name)) method = *builtin;
  else method = plugins().integrator(name);
  if (!method) throw InputError(unknown_integrator(path, name));
  if (method->needs_mechanical() && !scene.is_mechanical()) {  // the file's own integrator was checked by the loader
    // A plug-in's step(x, v) need not be symplectic (a student's explicit Euler): it steps bodies.
    // What can run this scene: the built-in first-order methods, and the plug-ins' own.
    std::string first_order = first_order_integrator_names();
    for (const auto& m : plugins().integrators())
      if (!m.needs_mechanical()) first_order += ", " + m.name();
    throw InputError(path + ": --integrator: " + name +
                     (method->is_external() ? " steps bodies (x and v) and needs a mechanical scene (bodies), and this "
                                              "is a first-order system; use "
                                            : " is symplectic and needs a mechanical scene (bodies); use ") +
                     first_order);
  }
  return *method;
}

std::string safe_file_name(const std::string& name) {
  std::string safe;
  for (char c : name) {
    const bool keep = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                      c == '-' || c == '_';
    safe += keep ? c : '_';
  }
  while (!safe.empty() && (safe.front() == '.' || safe.front() == '_')) safe.erase(safe.begin());
  if (safe.size() > 64) safe.resize(64);
  while (!safe.empty() && (safe.back() == '.' || safe.back() == '_')) safe.pop_back();
  return safe.empty() ? "scene" : safe;
}

std::string one_line(const std::string& text, size_t limit) { return one_printable_line(text, limit); }

long checked_step_count(double duration, double dt, const std::string& what) {
  const double steps = duration / dt;
  if (!(steps <= kMaxSteps))
    throw InputError(what + ": " + fmt::format("{:g}", steps) + " steps of " + fmt::format("{:g}", dt) +
                     " is more than a run can take (at most " + fmt::format("{:g}", kMaxSteps) + ")");
  // A duration this small against dt cannot be told from the rounding of a time (which takes no
  // step), so it would be run as no step at all.
  if (steps < 1e-9)
    throw InputError(what + ": dt = " + fmt::format("{:g}", dt) + " is more than 10^9 times the duration (" +
                     fmt::format("{:g}", duration) + "): the run would take no step");
  return fixed_step_count(duration, dt);
}

void check_position_resolution(const SceneDescription& scene, double dt, const std::string& path) {
  if (const auto coarse = positions_too_coarse(scene, dt))
    throw InputError(path + ": " + coarse->field() + ": " + coarse->what());
}

void check_time_resolution(double start_time, double duration, double dt, const std::string& start_what,
                           const std::string& step_what) {
  // The times t0 + i·dt must be told apart: far from 0 doubles are too coarse (at 1e17 they are
  // 16 apart), and the steps would land on the wrong times or on the same one. The field to
  // blame is start_time when it is what takes the run far from 0, else dt (or the duration).
  const double end = start_time + duration;
  const double far = std::max(std::abs(start_time), std::abs(end));
  const double spacing = std::nextafter(far, INFINITY) - far;
  if (spacing <= 1e-6 * dt) return;
  const double at = std::abs(start_time) > std::abs(end) ? start_time : end;  // (with its sign: t = -1e308)
  const std::string coarse = "at t = " + fmt::format("{:g}", at) + " times are " + fmt::format("{:g}", spacing) +
                             " apart, too coarse for steps of " + fmt::format("{:g}", dt);
  if (std::abs(start_time) > duration) throw InputError(start_what + ": " + coarse + " (start nearer t = 0)");
  // (With --steps, dt scales the times and their spacing alike: only the count can change. From
  // t = 0 the times are told apart up to the end of the largest binade [2^e, 2^(e+1)) whose spacing
  // 2^(e-52) is at most 1e-6·dt: between 1e-6·2^52 ≈ 4.5e9 and twice that many steps, by where dt
  // falls between two powers of two — 2^33 − 1 at dt = 1.)
  if (step_what == "--steps") {
    const int e = std::ilogb(1e-6 * dt) + 52;
    const double most = std::ceil(std::ldexp(1.0, e + 1) / dt) - 1;
    throw InputError(fmt::format("{}: {} (fewer steps: from t = 0, at most {:.3g} of {:g})", step_what, coarse, most, dt));
  }
  throw InputError(step_what + ": " + coarse + " (a larger dt or a shorter duration)");
}

fs::path without_trailing_separators(const std::string& path) {
  fs::path target(path);
  while (!target.has_filename() && target.has_relative_path()) target = target.parent_path();
  return target;
}

std::vector<std::string> module_candidates(const char* env_var, const std::string& name, const std::string& installed) {
  if (const char* env = std::getenv(env_var); env && *env) return {env};
  const fs::path here = executable_directory();
  return {(here / name).string(), (here / installed).lexically_normal().string()};
}

std::string default_run_folder(const std::string& kind, const std::string& scene_name) {
  const std::time_t now = std::time(nullptr);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  return fmt::format("runs/{}-{}-{}", kind, safe_file_name(scene_name), stamp);  // (a scene's name is not a path)
}

std::vector<std::string> folders_not_there_yet(const std::string& folder) {
  std::vector<std::string> missing;
  std::error_code ignored;
  for (fs::path above = folder; !above.empty() && !fs::exists(fs::symlink_status(above, ignored));
       above = above.parent_path()) {
    missing.push_back(above.string());
    if (above == above.parent_path()) break;
  }
  return missing;
}

std::string why_not_created(const std::string& folder, const std::error_code& error) {
  // A link to nothing on the way ("runs" left pointing at a folder since removed): create_directories
  // says only "File exists", which sends the reader looking for a file that is not there.
  std::error_code ignored;
  for (fs::path above = folder; !above.empty(); above = above.parent_path()) {
    if (fs::is_symlink(fs::symlink_status(above, ignored)) && !fs::exists(fs::status(above, ignored)))
      return above.string() + " is a link to " + fs::read_symlink(above, ignored).string() + ", which does not exist";
    if (above == above.parent_path()) break;
  }
  return error.message();
}

namespace {
std::string said_as_final(std::string message, const std::string& partial, const std::string& final) {
  if (partial.empty()) return message;
  for (size_t at = message.find(partial); at != std::string::npos; at = message.find(partial, at + final.size()))
    message.replace(at, partial.size(), final);
  return message;
}

struct SaidAsFinal {
  std::mutex lock;  // (grade --batch writes its results from several threads)
  std::vector<std::pair<std::string, std::string>> names;  // partial, final
};
SaidAsFinal& said_as_final_names() {
  static SaidAsFinal names;
  return names;
}
}  // namespace

void say_as_final(const std::string& partial, const std::string& final) {
  SaidAsFinal& said = said_as_final_names();
  const std::lock_guard<std::mutex> hold(said.lock);
  for (auto& [from, to] : said.names)
    if (from == partial) {
      to = final;
      return;
    }
  said.names.emplace_back(partial, final);
}

void say_as_it_is(const std::string& partial) {
  SaidAsFinal& said = said_as_final_names();
  const std::lock_guard<std::mutex> hold(said.lock);
  std::erase_if(said.names, [&](const auto& name) { return name.first == partial; });
}

std::string named_as_final(std::string message) {
  SaidAsFinal& said = said_as_final_names();
  const std::lock_guard<std::mutex> hold(said.lock);
  // (the latest first: a file's own temporary folder inside a run's, "r.partial-X/.f.partial-Y/f")
  for (auto name = said.names.rbegin(); name != said.names.rend(); ++name)
    message = said_as_final(std::move(message), name->first, name->second);
  return message;
}

void remove_if_empty(const std::vector<std::string>& folders) {
  for (const auto& folder : folders) {
    // ("x/./y" and "a/b/../c" list x/. and a/b/..: no folders of their own, and no reason to stop)
    if (const fs::path name = fs::path(folder).filename(); name == "." || name == "..") continue;
    std::error_code error;
    fs::remove(folder, error);  // (one already gone counts as removed: render's --out, taken with its frames)
    if (error) return;          // not empty: it and the folders above it stay
  }
}

PartialFolder::PartialFolder(const std::string& final_path, bool numbered)
    : final_(without_trailing_separators(final_path).string()), numbered_(numbered) {
  const fs::path target(final_);
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code error;
  made_parents_ = folders_not_there_yet(parent.string());  // (made now; removed again if the work never gets there)
  fs::create_directories(parent, error);
  if (error) throw InputError(final_ + ": cannot be created (" + why_not_created(parent.string(), error) + ")");
  std::string pattern = (parent / partial_name_for(target.filename().string())).string();
  if (!::mkdtemp(pattern.data())) {
    const std::string why = std::strerror(errno);
    remove_if_empty(made_parents_);
    throw InputError(final_ + ": cannot be created (" + why + ")");
  }
  // As a folder made by create_directories would be (mkdtemp makes 0700): 0777 less the umask.
  const mode_t umask = ::umask(0);
  ::umask(umask);
  ::chmod(pattern.c_str(), 0777 & ~umask);
  partial_ = pattern;
  say_as_final(partial_, final_);
}

PartialFolder::~PartialFolder() {
  if (done_) return;
  std::error_code ignored;
  fs::remove_all(partial_, ignored);
  remove_if_empty(made_parents_);
}

namespace {
// Renames `from` to `to` unless something is at `to` already (then false; the check and the rename
// are one step, RENAME_NOREPLACE, so nothing that appears in between is replaced). A file system
// without that flag gets a hard link and an unlink instead, which refuse the same way (files only).
bool rename_without_replacing(const std::string& from, const std::string& to) {
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return true;
  if (errno == EEXIST) return false;
  if (errno == EINVAL || errno == ENOSYS) {
    if (::link(from.c_str(), to.c_str()) == 0) {
      ::unlink(from.c_str());
      return true;
    }
    if (errno == EEXIST) return false;
  }
  throw std::runtime_error(to + ": could not be written (" + std::strerror(errno) + ")");
}
}  // namespace

const std::string& PartialFolder::complete() {
  const std::string name = final_;
  for (int n = 2; !rename_without_replacing(partial_, final_); ++n) {
    if (!numbered_ || n > 100000) {
      done_ = true;  // (kept where the message says it is)
      say_as_it_is(partial_);
      throw std::runtime_error(final_ + ": appeared while the report was written; it is in " + partial_);
    }
    final_ = name + "-" + std::to_string(n);
  }
  done_ = true;
  say_as_final(partial_, final_);  // (numbered: where it is now)
  return final_;
}

PartialFile::PartialFile(const std::string& final_path) : final_(final_path) {
  std::string pattern = partial_folder_pattern_for(final_path);
  if (!::mkdtemp(pattern.data()))
    throw InputError(final_ + ": cannot be written (" + std::string(std::strerror(errno)) + ")");
  folder_ = pattern;
  file_ = (fs::path(folder_) / fs::path(final_path).filename()).string();
  say_as_final(file_, final_);
}

PartialFile::~PartialFile() {
  if (done_) return;
  std::error_code ignored;
  fs::remove_all(folder_, ignored);
}

void PartialFile::complete(bool overwrite) {
  std::error_code error;
  if (overwrite) {
    // The file replaced keeps its permissions: a user's 0600 file came back 0644, readable by all.
    // (A link in its place is replaced, not written through: what it points to may be outside the
    // folder the user gave.)
    struct stat replaced {};
    if (::lstat(final_.c_str(), &replaced) == 0 && S_ISREG(replaced.st_mode))
      ::chmod(file_.c_str(), replaced.st_mode & 07777);
    fs::rename(file_, final_, error);
    if (error) throw std::runtime_error(final_ + ": could not be written (" + error.message() + ")");
  } else if (!rename_without_replacing(file_, final_)) {
    done_ = true;  // (kept: it is the only copy of the work)
    say_as_it_is(file_);
    throw std::runtime_error(final_ + ": appeared while it was written, and is left as it is (no --overwrite); what was "
                                      "written is in " + file_);
  }
  done_ = true;
  fs::remove(folder_, error);
}

bool written_in_place(const std::string& path) {
  std::error_code ignored;
  const auto status = fs::status(path, ignored);
  return fs::exists(status) && !fs::is_regular_file(status);
}

void write_whole_file(const std::string& path, const std::string& text, bool overwrite) {
  std::optional<PartialFile> partial;
  if (!written_in_place(path)) partial.emplace(path);
  {
    std::ofstream out(partial ? partial->path() : path, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error(path + ": cannot be written (" + std::strerror(errno) + ")");
    errno = 0;
    out << text;
    out.flush();
    if (!out) throw std::runtime_error(plot::write_failure(path));
  }
  if (partial) partial->complete(overwrite);
}

fs::file_status looked_at(const std::string& path, const std::string& option) {
  std::error_code error;
  const auto status = fs::status(path, error);
  if (error && error != std::errc::no_such_file_or_directory && error != std::errc::not_a_directory)
    throw InputError(path + ": " + (option.empty() ? "" : option + ": ") + error.message());
  return status;
}

bool output_exists(const std::string& path) {
  // (Nothing there, or a part of the way that is a file, is for the folder's making to report.)
  auto absent = [](const std::error_code& e) {
    return !e || e == std::errc::no_such_file_or_directory || e == std::errc::not_a_directory;
  };
  std::error_code error;
  // ("f/" is f: a file or a dangling link there is f's, though "f/" itself names nothing)
  const auto status = fs::symlink_status(without_trailing_separators(path), error);  // (fails through a loop of links on the way, too)
  if (!absent(error)) throw InputError(path + ": " + error.message());
  return fs::exists(status);
}

void check_can_write(const std::string& path, bool overwrite) {
  std::error_code error;
  const auto status = fs::status(path, error);
  // (A FIFO or a device is no file the user wrote: it is written as it is, below — also through a
  // link to one, as /dev/stderr is when it is a terminal or a pipe.)
  const auto link_status = fs::symlink_status(path, error);
  const bool link = fs::is_symlink(link_status);
  const bool to_a_device = link && fs::exists(status) && !fs::is_regular_file(status) && !fs::is_directory(status);
  // A link to an open descriptor (/dev/stderr → /proc/self/fd/2) whose file is a regular one: with
  // --overwrite the link itself was replaced (as root, /dev/stdout became a file of rows).
  if (link && !to_a_device) {
    const fs::path target = fs::read_symlink(path, error);
    if (!error && target.string().starts_with("/proc/"))
      throw InputError(path + ": is a link to an open file (" + target.string() +
                       "); motus writes no file through a link: for standard output, use -");
  }
  if ((fs::is_regular_file(link_status) || link) && !to_a_device && !overwrite)
    throw InputError(path + ": already exists; choose another name or pass --overwrite");
  if (fs::is_directory(status)) throw InputError(path + ": is a folder, not a file");
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty()) {
    // (a loop of links or a name too long on the way: what the system says, not "does not exist")
    const auto folder = fs::status(parent, error);
    if (error && error != std::errc::no_such_file_or_directory && error != std::errc::not_a_directory)
      throw InputError(path + ": " + error.message());
    if (!fs::is_directory(folder))
      throw InputError(path + ": folder " + parent.string() + (fs::exists(folder) ? " is a file" : " does not exist"));
  }
  // A file beside it, made and removed at once: a folder that takes no new file (/proc, a
  // read-only disk) or a name too long is bad input now, not a failure after the work. (A FIFO
  // or a device is written as it is, and needs no new file.)
  if (fs::exists(status) && !fs::is_regular_file(status)) return;
  const fs::path folder = parent.empty() ? fs::path(".") : parent;
  // (The file itself is written in a folder with a longer name, a PartialFile's, then moved.)
  const long name_max = ::pathconf(folder.c_str(), _PC_NAME_MAX);
  const std::string name = fs::path(path).filename().string();
  if (name_max > 0 && (static_cast<long>(name.size()) > name_max ||
                       static_cast<long>(partial_name_for(name).size()) > name_max))
    throw InputError(path + ": the file name is too long (at most " + std::to_string(std::min<long>(name_max, NAME_MAX)) +
                     " bytes here)");
  const std::string probe = (folder / (".motus-probe-" + std::to_string(::getpid()))).string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0 && errno != EEXIST) throw InputError(path + ": cannot be written there (" + std::strerror(errno) + ")");
  if (fd >= 0) ::close(fd), ::unlink(probe.c_str());
}

// (A legal name of 240–255 bytes was refused as "File name too long", or failed after its work.)
std::string partial_name_for(const std::string& name) {
  const std::string named = "." + name + ".partial-XXXXXX";
  return named.size() <= NAME_MAX ? named : std::string(".partial-XXXXXX");
}

std::string partial_folder_pattern_for(const std::string& path) {
  const fs::path target(path);
  return (target.parent_path() / partial_name_for(target.filename().string())).string();
}

void check_can_replace(const std::string& path, bool overwrite) {
  check_can_write(path, overwrite);
  std::error_code error;
  const auto status = fs::symlink_status(path, error);
  if (fs::exists(status) && !fs::is_regular_file(status) && !fs::is_symlink(status))
    throw InputError(path + ": is not a regular file (a device or a FIFO); --overwrite replaces regular files only");
}

const CLI::Validator& non_empty_path() {
  static const CLI::Validator validator(
      [](const std::string& path) { return path.empty() ? std::string("an empty path names no file") : std::string(); },
      "PATH");
  return validator;
}

CLI::Validator folder_path(const std::string& what) {
  return CLI::Validator(
      [what](const std::string& path) {
        if (path.empty()) return "an empty path names no " + what;
        const std::string last = without_trailing_separators(path).filename().string();
        if (last == "." || last == "..")
          return "ends in \"" + last + "\": name the new " + what + " itself, by its own name";
        return std::string();
      },
      "PATH");
}

namespace {

// The whole number `text` is in decimal, all of it, or nothing.
std::optional<long> decimal_whole_number(const std::string& text) {
  long value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

}  // namespace

CLI::Validator whole_number_in(long low, long high) {
  return CLI::Validator(
      [low, high](std::string& text) {
        if (const auto value = decimal_whole_number(text); value && *value >= low && *value <= high) {
          text = std::to_string(*value);  // (as read: CLI11 would read "010" as octal, 8)
          return std::string();
        }
        return fmt::format("must be a whole number from {} to {} (got {})", low, high, one_line(text, 40));
      },
      fmt::format("INT in [{} - {}]", low, high));
}

CLI::Validator a_number() {
  return CLI::Validator(
      [](std::string& text) {
        // Blanks around a number are dropped on both sides alike (C's reading took " 1" and refused "1 ").
        const auto blank = [](unsigned char c) { return std::isspace(c) != 0; };
        while (!text.empty() && blank(text.back())) text.pop_back();
        text.erase(text.begin(), std::find_if_not(text.begin(), text.end(), blank));
        return text.empty() ? std::string("\"\" is not a number") : std::string();
      },
      "");
}

CLI::Validator read_as_decimal() {
  return CLI::Validator(
      [](std::string& text) {
        if (const auto value = decimal_whole_number(text)) text = std::to_string(*value);
        return std::string();  // (anything else: CLI11's own conversion refuses it)
      },
      "");
}

std::string time_unit_of(const SceneDescription& scene) {
  if (scene.first_order)
    if (const auto* info = find_first_order_system(scene.first_order->type); info && info->time_unit == "year")
      return "years";
  return "s";
}

double load_average() {
  const char* file = std::getenv("MOTUS_LOADAVG");
  std::ifstream in(file && *file ? file : "/proc/loadavg");
  double load = NAN;
  return in >> load ? load : NAN;
}

long online_cores() {
  const long cores = ::sysconf(_SC_NPROCESSORS_ONLN);
  return cores > 0 ? cores : 0;
}

}  // namespace motus::cli
