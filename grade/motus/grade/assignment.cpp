#include "motus/grade/assignment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "motus/scene_error.hpp"
#include "motus/scene_file/json_fields.hpp"
#include "motus/scene_file/scene_file.hpp"
#include "motus/scene_file/strict_json.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace motus::grade {
namespace {

json read_json(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw AssignmentError(file.string() + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  // As strictly as a scene: a key written twice ("points" twice in one rubric entry) would
  // otherwise count once, the last, and a NUL byte would end the file unseen.
  try {
    return parse_strict_json(text.str(), file.string());
  } catch (const SceneFileError& e) {
    throw AssignmentError(e.what());
  }
}

// An optional array of strings (JsonFields has no reader of its own for one).
std::vector<std::string> strings(JsonFields& f, const std::string& key) {
  std::vector<std::string> out;
  if (!f.has(key)) return out;
  f.use(key);
  const json& a = f.raw().at(key);
  if (!a.is_array()) f.fail(key, "must be an array of strings, not " + json_type_name(a));
  for (size_t i = 0; i < a.size(); ++i) {
    if (!a[i].is_string()) f.fail(key + "[" + std::to_string(i) + "]", "must be a string, not " + json_type_name(a[i]));
    out.push_back(a[i].get<std::string>());
  }
  return out;
}

// assignment.json and rubric.json are read as strictly as a test is (JsonFields): a field misspelt
// or of the wrong type is the instructor's mistake, named, never a default ("pionts" gave a test
// 0 points; "visibilty" showed an after_due_date test to the students at once).
AssignmentError in_file(const std::string& file, const SceneError& e) {
  return AssignmentError(file + ": " + e.field() + ": " + e.what());
}

struct RubricEntry {
  std::string name, visibility;
  double points;
};

// rubric.json: {"tests": [{"name", "points", "visibility"}, ...]}, every field required.
std::vector<RubricEntry> read_rubric(const std::string& rubric_file) {
  const json rubric = read_json(rubric_file);
  if (!rubric.is_object() || !rubric.contains("tests") || !rubric.at("tests").is_array())
    throw AssignmentError(rubric_file + ": tests: must be an array of {name, points, visibility}");
  static const std::set<std::string> visibilities = {"visible", "after_due_date", "after_published", "hidden"};
  std::vector<RubricEntry> entries;
  std::set<std::string> names;
  try {
    JsonFields top(rubric, "");
    for (auto& f : top.objects("tests")) {
      // The known fields are asked for first, so that a misspelt one is named as unknown rather
      // than as the one it was meant to be, missing.
      for (const char* key : {"name", "points", "visibility"}) f.use(key);
      f.reject_unknown();
      RubricEntry e;
      e.name = f.string("name");
      if (!names.insert(e.name).second) f.fail("name", "\"" + e.name + "\" is in the rubric twice");
      e.points = f.number("points");
      if (!(e.points >= 0) || e.points > 1e6) f.fail("points", "must be a number from 0 to 1,000,000");
      e.visibility = f.string("visibility");
      if (!visibilities.count(e.visibility))
        f.fail("visibility", "must be visible, after_due_date, after_published or hidden");
      entries.push_back(e);
    }
    top.reject_unknown();
  } catch (const SceneError& e) {
    throw in_file(rubric_file, e);
  }
  return entries;
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
  // (An empty folder, or the wrong one, read as no hidden tests at all: the error was the rubric's,
  // "defined in no test file", for its first hidden test.)
  if (hidden && files.empty())
    throw AssignmentError(folder.string() + ": --hidden: holds no .json test files (every .json directly in it is read "
                                            "as a file of tests); is that the hidden tests' folder?");
  // What a file there is: every one is read as a file of tests (a test's scene files go in a
  // folder of their own beside them, scenes/, and are named by scene_file).
  const std::string every = "every .json directly in " + folder.string() +
                            " is read as a file of tests, {\"tests\": [...]} (a test's scene files go in a "
                            "subfolder, such as scenes/, and are named by scene_file)";
  for (const auto& file : files) {
    const json document = read_json(file);
    if (!document.is_object())
      throw AssignmentError(file.string() + ": must be an object, not " + json_type_name(document) + ": " + every);
    // A test file holds its tests and nothing else: a misspelt "tests" beside the real one (or a
    // second list, "hidden_tests") would otherwise be skipped without a word.
    try {
      JsonFields top(document, "");
      // (A misspelt "test" is named as such by fail: "unknown field, did you mean tests?".)
      if (!document.contains("tests")) top.fail("tests", "missing (required): " + every);
      if (!document.at("tests").is_array())
        top.fail("tests", "must be an array of tests, not " + json_type_name(document.at("tests")));
      top.use("tests");
      top.reject_unknown();
    } catch (const SceneError& e) {
      throw in_file(file.string(), e);
    }
    const json& tests = document.at("tests");
    for (size_t i = 0; i < tests.size(); ++i) {
      const std::string path = "tests[" + std::to_string(i) + "]";
      if (!tests[i].is_object() || !tests[i].contains("name") || !tests[i].at("name").is_string())
        throw AssignmentError(file.string() + ": " + path + ".name: every test needs a name");
      const std::string name = tests[i].at("name").get<std::string>();
      if (into.count(name)) {
        const Definition& first = into.at(name);
        throw AssignmentError(file.string() + ": " + path + ".name: \"" + name + "\" is defined twice (also as " +
                              first.path + (first.file == file.string() ? " of this file" : " in " + first.file) + ")");
      }
      into[name] = {tests[i], file.string(), path, hidden};
    }
  }
}

// C++ source with its comments blanked out (string and character literals kept as they are).
std::string without_comments(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size();) {
    if (s.compare(i, 2, "//") == 0) {
      while (i < s.size() && s[i] != '\n') ++i;
    } else if (s.compare(i, 2, "/*") == 0) {
      const size_t end = s.find("*/", i + 2);
      i = end == std::string::npos ? s.size() : end + 2;
      out += ' ';
    } else if (s[i] == '"' || s[i] == '\'') {
      const char quote = s[i];
      out += s[i++];
      while (i < s.size() && s[i] != quote && s[i] != '\n') {
        if (s[i] == '\\' && i + 1 < s.size()) out += s[i++];
        out += s[i++];
      }
      if (i < s.size()) out += s[i++];
    } else {
      out += s[i++];
    }
  }
  return out;
}

}  // namespace

StudentParts read_plugin_parts(const std::string& folder, const std::vector<std::string>& provided) {
  StudentParts parts;
  static const std::set<std::string> sources = {".cpp", ".cc", ".cxx", ".hpp", ".h", ".hh", ".hxx", ".ipp"};
  static const std::regex plugin(R"re(\bMOTUS_PLUGIN\s*\()re"), named(R"re(^\s*"([^"\\]*)")re");
  static const std::regex call(
      R"re((\.|->)\s*(first_order|mechanical|position_verlet|adaptive|collisions|constraints)\s*\()re");
  int plugins = 0;
  bool whole = true;
  for (const auto& name : provided) {
    if (!sources.count(fs::path(name).extension().string())) continue;
    std::ifstream in(fs::path(folder) / name, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    const std::string source = without_comments(text.str());
    for (auto it = std::sregex_iterator(source.begin(), source.end(), plugin); it != std::sregex_iterator(); ++it) {
      ++plugins;
      std::smatch m;
      const std::string after = source.substr(static_cast<size_t>(it->position() + it->length()), 200);
      if (std::regex_search(after, m, named)) parts.prefix = m[1];
      else whole = false;
      parts.file = name;
    }
    for (auto it = std::sregex_iterator(source.begin(), source.end(), call); it != std::sregex_iterator(); ++it) {
      const std::string kind = (*it)[2];
      if (kind == "collisions") parts.collisions = true;
      else if (kind == "constraints") parts.constraints = true;
      else {
        std::smatch m;
        const std::string after = source.substr(static_cast<size_t>(it->position() + it->length()), 200);
        if (std::regex_search(after, m, named)) parts.integrators.push_back({m[1].str(), kind});
        else whole = false;  // a name made at run time: not known here
      }
    }
  }
  // (Named as a test names them, PREFIX:NAME, once the file that holds MOTUS_PLUGIN has been read.)
  for (auto& i : parts.integrators) i.name = parts.prefix + ":" + i.name;
  parts.known = plugins == 1 && whole && !parts.prefix.empty();
  return parts;
}

std::string Assignment::not_given_when() const {
  static const std::pair<const char*, const char*> words[] = {{"visible", "shown at once"},
                                                               {"after_due_date", "shown after the due date"},
                                                               {"after_published", "shown once the grades are published"},
                                                               {"hidden", "never shown"}};
  std::string when;
  for (const auto& [visibility, shown] : words)
    if (const auto it = not_given_by_visibility.find(visibility); it != not_given_by_visibility.end() && it->second > 0)
      when += fmt::format("{}{} {}", when.empty() ? "" : ", ", it->second, shown);
  return when;
}

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
  try {
    JsonFields f(manifest, "");
    a.name = f.string("name", root.filename().string());
    a.title = f.string("title", a.name);
    a.files = strings(f, "files");
    a.provided = strings(f, "provided");
    a.flags = strings(f, "flags");
    a.starter_passes = strings(f, "starter_passes");
    a.timeout_hint = f.string("timeout_hint", "");
    f.reject_unknown();
  } catch (const SceneError& e) {
    throw in_file(manifest_file, e);
  }
  if (a.files.empty()) throw AssignmentError(manifest_file + ": files: name at least one file the student hands in");
  for (const auto& f : a.files) check_file_name(f, manifest_file + ": files");
  for (const auto& f : a.provided) {
    check_file_name(f, manifest_file + ": provided");
    if (!fs::is_regular_file(root / f)) throw AssignmentError(manifest_file + ": provided: " + f + " is not in " + folder);
  }
  for (const auto& flag : a.flags)
    if (flag.empty() || flag[0] != '-' || flag.find("-o") == 0 || flag.find("-fplugin") == 0 || flag.find('@') != std::string::npos)
      throw AssignmentError(manifest_file + ": flags: \"" + flag + "\" is not a compiler flag motus passes on");

  // What the tests may run of the student's: the plug-in's integrators, collision rules, projection.
  a.parts = read_plugin_parts(folder, a.provided);

  std::map<std::string, Definition> definitions;
  read_definitions(root / "tests", false, definitions);
  if (hidden) read_definitions(*hidden, true, definitions);

  const std::string rubric_file = (root / "rubric.json").string();
  const std::vector<RubricEntry> rubric = read_rubric(rubric_file);
  std::set<std::string> in_rubric;
  SceneSource scenes = scenes_in;
  for (size_t i = 0; i < rubric.size(); ++i) {
    const auto& [name, visibility, points] = rubric[i];
    in_rubric.insert(name);
    const std::string where = rubric_file + ": tests[" + std::to_string(i) + "]";
    const auto it = definitions.find(name);
    if (it == definitions.end()) {
      if (!hidden) {
        ++a.hidden_not_given;  // a hidden test, and the hidden tests were not given
        if (visibility == "after_due_date" || visibility == "after_published") ++a.hidden_shown_later;
        ++a.not_given_by_visibility[visibility];
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
      t.catches = strings(f, "catches");
      if (f.has("counts_with_one_of")) {
        t.counts_with_one_of = strings(f, "counts_with_one_of");
        if (t.counts_with_one_of.empty())
          throw AssignmentError(d.file + ": " + d.path + ".counts_with_one_of: names no test (leave it out instead)");
      }
      t.check = make_check(f, scenes, a.parts, t.hint);
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
