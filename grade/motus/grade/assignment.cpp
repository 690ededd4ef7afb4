#include "motus/grade/assignment.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "motus/scene_error.hpp"
#include "motus/scene_file/scene_file.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace motus::grade {
namespace {

json read_json(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw AssignmentError(file.string() + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  try {
    return json::parse(text.str());
  } catch (const json::parse_error& e) {
    throw AssignmentError(file.string() + ": not valid JSON: " + e.what());
  }
}

std::vector<std::string> strings(const json& object, const std::string& key, const std::string& file) {
  std::vector<std::string> out;
  if (!object.contains(key)) return out;
  const json& a = object.at(key);
  if (!a.is_array()) throw AssignmentError(file + ": " + key + ": must be an array of strings");
  for (size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_string()) throw AssignmentError(file + ": " + key + "[" + std::to_string(i) + "]: must be a string");
    out.push_back(a[i].get<std::string>());
  }
  return out;
}

// A file name the student hands in or the assignment provides: a plain name, never a path.
void check_file_name(const std::string& name, const std::string& where) {
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == ".." || name[0] == '.')
    throw AssignmentError(where + ": \"" + name + "\" must be a plain file name (no folders, not hidden)");
}

struct Definition {
  json test;
  std::string file, path;
  bool hidden;
};

void read_definitions(const fs::path& folder, bool hidden, std::map<std::string, Definition>& into) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) throw AssignmentError(folder.string() + ": no such folder of tests");
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    const json document = read_json(file);
    if (!document.is_object() || !document.contains("tests") || !document.at("tests").is_array())
      throw AssignmentError(file.string() + ": tests: must be an array of tests");
    const json& tests = document.at("tests");
    for (size_t i = 0; i < tests.size(); ++i) {
      const std::string path = "tests[" + std::to_string(i) + "]";
      if (!tests[i].is_object() || !tests[i].contains("name") || !tests[i].at("name").is_string())
        throw AssignmentError(file.string() + ": " + path + ".name: every test needs a name");
      const std::string name = tests[i].at("name").get<std::string>();
      if (into.count(name))
        throw AssignmentError(file.string() + ": " + path + ".name: \"" + name + "\" is defined twice (also in " +
                              into.at(name).file + ")");
      into[name] = {tests[i], file.string(), path, hidden};
    }
  }
}

}  // namespace

double Assignment::max_score() const {
  double total = 0;
  for (const auto& t : tests) total += t.points;
  return total;
}

Assignment load_assignment(const std::string& folder, const std::optional<std::string>& hidden,
                           const SceneSource& scenes_in) {
  Assignment a;
  // Absolute: the sandbox mounts its provided files by this path (bubblewrap resolves a relative
  // one from elsewhere, and the build would fail as if the student's code did not compile).
  a.folder = fs::absolute(folder).lexically_normal().string();
  const fs::path root(folder);
  const std::string manifest_file = (root / "assignment.json").string();
  if (!fs::is_regular_file(manifest_file)) throw AssignmentError(folder + ": not an assignment (no assignment.json)");
  const json manifest = read_json(manifest_file);
  if (!manifest.is_object()) throw AssignmentError(manifest_file + ": must be an object");
  a.name = manifest.value("name", root.filename().string());
  a.title = manifest.value("title", a.name);
  a.files = strings(manifest, "files", manifest_file);
  a.provided = strings(manifest, "provided", manifest_file);
  a.flags = strings(manifest, "flags", manifest_file);
  a.starter_passes = strings(manifest, "starter_passes", manifest_file);
  if (manifest.contains("timeout_hint") && !manifest.at("timeout_hint").is_string())
    throw AssignmentError(manifest_file + ": timeout_hint: must be a string");
  a.timeout_hint = manifest.value("timeout_hint", std::string());
  if (a.files.empty()) throw AssignmentError(manifest_file + ": files: name at least one file the student hands in");
  for (const auto& f : a.files) check_file_name(f, manifest_file + ": files");
  for (const auto& f : a.provided) {
    check_file_name(f, manifest_file + ": provided");
    if (!fs::is_regular_file(root / f)) throw AssignmentError(manifest_file + ": provided: " + f + " is not in " + folder);
  }
  for (const auto& flag : a.flags)
    if (flag.empty() || flag[0] != '-' || flag.find("-o") == 0 || flag.find("-fplugin") == 0 || flag.find('@') != std::string::npos)
      throw AssignmentError(manifest_file + ": flags: \"" + flag + "\" is not a compiler flag motus passes on");

  std::map<std::string, Definition> definitions;
  read_definitions(root / "tests", false, definitions);
  if (hidden) read_definitions(*hidden, true, definitions);

  const std::string rubric_file = (root / "rubric.json").string();
  const json rubric = read_json(rubric_file);
  if (!rubric.is_object() || !rubric.contains("tests") || !rubric.at("tests").is_array())
    throw AssignmentError(rubric_file + ": tests: must be an array of {name, points, visibility}");
  static const std::set<std::string> visibilities = {"visible", "after_due_date", "after_published", "hidden"};
  std::set<std::string> in_rubric;
  SceneSource scenes = scenes_in;
  for (size_t i = 0; i < rubric.at("tests").size(); ++i) {
    const json& entry = rubric.at("tests")[i];
    const std::string where = rubric_file + ": tests[" + std::to_string(i) + "]";
    if (!entry.is_object() || !entry.contains("name") || !entry.at("name").is_string())
      throw AssignmentError(where + ".name: every rubric entry names a test");
    const std::string name = entry.at("name").get<std::string>();
    if (!in_rubric.insert(name).second) throw AssignmentError(where + ".name: \"" + name + "\" is in the rubric twice");
    const double points = entry.value("points", 0.0);
    if (!(points >= 0) || points > 1e6) throw AssignmentError(where + ".points: must be a number from 0 to 1,000,000");
    const std::string visibility = entry.value("visibility", std::string("visible"));
    if (!visibilities.count(visibility))
      throw AssignmentError(where + ".visibility: must be visible, after_due_date, after_published or hidden");
    const auto it = definitions.find(name);
    if (it == definitions.end()) {
      if (!hidden) {
        ++a.hidden_not_given;  // a hidden test, and the hidden tests were not given
        if (visibility == "after_due_date" || visibility == "after_published") ++a.hidden_shown_later;
        continue;
      }
      throw AssignmentError(where + ".name: \"" + name + "\" is defined in no test file: not in " + (root / "tests").string() +
                            "/ nor in --hidden " + *hidden + " (is that the hidden tests' folder?)");
    }
    const Definition& d = it->second;
    TestCase t;
    t.name = name;
    t.points = points;
    t.visibility = visibility;
    t.file = d.file;
    t.hidden = d.hidden;
    scenes.tests_folder = fs::path(d.file).parent_path().string();
    try {
      JsonFields f(d.test, d.path);
      f.string("name");
      t.title = f.string("title", name);
      t.hint = f.string("hint", "");
      if (d.test.contains("catches")) {
        f.use("catches");
        t.catches = strings(d.test, "catches", d.file + ": " + d.path);
      }
      if (d.test.contains("counts_with_one_of")) {
        f.use("counts_with_one_of");
        t.counts_with_one_of = strings(d.test, "counts_with_one_of", d.file + ": " + d.path);
        if (t.counts_with_one_of.empty())
          throw AssignmentError(d.file + ": " + d.path + ".counts_with_one_of: names no test (leave it out instead)");
      }
      t.check = make_check(f, scenes, t.hint);
      f.reject_unknown();
    } catch (const SceneFileError& e) {
      throw AssignmentError(d.file + ": " + d.path + ": " + e.what());
    } catch (const SceneError& e) {
      throw AssignmentError(d.file + ": " + (e.field().empty() ? d.path : e.field()) + ": " + e.what());
    } catch (const json::exception& e) {
      throw AssignmentError(d.file + ": " + d.path + ": " + e.what());
    }
    a.tests.push_back(std::move(t));
  }
  for (const auto& [name, d] : definitions)
    if (!in_rubric.count(name))
      throw AssignmentError(d.file + ": " + d.path + ".name: \"" + name + "\" is not in the rubric (" + rubric_file + ")");
  // A test's gates are public tests of the rubric (run wherever it is: a student's own grading has
  // no hidden tests), never itself.
  for (const auto& t : a.tests)
    for (const auto& gate : t.counts_with_one_of) {
      const auto it = definitions.find(gate);
      if (gate == t.name || it == definitions.end() || it->second.hidden)
        throw AssignmentError(t.file + ": " + t.name + ": counts_with_one_of: \"" + gate + "\" is " +
                              (gate == t.name ? "the test itself" : "not a public test of the rubric"));
    }
  for (const auto& name : a.starter_passes)
    if (!in_rubric.count(name) && name != "files" && name != "build")
      throw AssignmentError(manifest_file + ": starter_passes: \"" + name + "\" is not in the rubric");
  return a;
}

}  // namespace motus::grade
