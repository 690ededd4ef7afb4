#include "locations.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "cli_common.hpp"
#include "motus/scene_file/spelling.hpp"

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

std::vector<std::string> shipped_scenes() {
  std::vector<std::string> files;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(scenes_directory(), error))
    if (entry.path().extension() == ".json") files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> module_candidates(const char* env_var, const std::string& name, const std::string& installed) {
  if (const char* env = std::getenv(env_var); env && *env) return {env};
  const fs::path here = executable_directory();
  return {(here / name).string(), (here / installed).lexically_normal().string()};
}

}  // namespace motus::cli
