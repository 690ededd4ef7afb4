#include "cli_common.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

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

std::string resolve_scene_path(const std::string& argument) {
  if (fs::exists(argument)) return argument;
  const bool plain_name = argument.find('/') == std::string::npos;
  if (plain_name) {
    fs::path shipped = fs::path(scenes_directory()) / argument;
    if (shipped.extension() != ".json") shipped += ".json";
    if (fs::exists(shipped)) return shipped.string();
  }
  return argument;  // the loader says "no such file"
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

void load_plugins(const std::vector<std::string>& files) {
  try {
    for (const auto& file : files) plugins().load(file);
  } catch (const PluginError& e) {
    throw InputError(e.what());
  }
  report_plugin_crashes(plugins());
}

std::string known_integrators() {
  std::string names = integrator_names();
  for (const auto& m : plugins().integrators()) names += ", " + m.name();
  return names;
}

Method method_for(const std::string& path, const SceneDescription& scene, const std::optional<std::string>& requested) {
  const std::string name = requested.value_or(scene.integrator);
  std::optional<Method> method;
  if (const auto builtin = integrator_from_name(name)) method = *builtin;
  else method = plugins().integrator(name);
  if (!method) {
    const bool looks_like_plugin = name.find(':') != std::string::npos;
    throw InputError(path + ": --integrator: unknown integrator \"" + name + "\" (known: " + known_integrators() + ")" +
                     (looks_like_plugin && plugins().empty() ? "; load its plug-in with --plugin FILE.so" : ""));
  }
  if (method->needs_mechanical() && !scene.is_mechanical())  // the file's own integrator was checked by the loader
    throw InputError(path + ": --integrator: " + name + " is symplectic and needs a mechanical scene (bodies); " +
                     "use euler, midpoint, rk4, rk4-doubling or rk45");
  return *method;
}

void check_can_write(const std::string& path, bool overwrite) {
  if (fs::exists(path) && !overwrite)
    throw InputError(path + ": already exists; choose another name or pass --overwrite");
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent)) throw InputError(path + ": folder " + parent.string() + " does not exist");
}

}  // namespace motus::cli
