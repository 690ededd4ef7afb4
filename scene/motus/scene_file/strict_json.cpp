// parse_strict_json (strict_json.hpp): JSON read as strictly as a scene file is, a malformed document
// named by line, column and field path; the scene loader and the grader both read their files through it.
#include "motus/scene_file/strict_json.hpp"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <string>

#include "motus/scene_file/scene_file.hpp"
#include "motus/scene_file/strict_json_sax.hpp"

namespace motus {
namespace {

[[noreturn]] void throw_parse_error(const std::string& text, const std::string& file, const nlohmann::json::exception& e,
                                    std::size_t byte) {
  FieldPathTracker tracker;
  nlohmann::json::sax_parse(text, &tracker);
  // A trailing comma ("duration": 1,}) stops the parser at the '}' or ']' after it: the error is the
  // object's or array's, not the last member's ("duration" was read whole), so FIELD names the
  // object or array (nothing at the top level).
  if (byte >= 1 && byte <= text.size() && (text[byte - 1] == '}' || text[byte - 1] == ']')) {
    size_t i = byte - 1;
    while (i > 0 && std::isspace(static_cast<unsigned char>(text[i - 1]))) --i;
    if (i > 0 && text[i - 1] == ',') tracker.forget_last_member();
  }
  // nlohmann reports a byte offset; people want a line and a column.
  size_t line = 1, column = 1;
  for (size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  std::string what = e.what();
  const auto bracket = what.find("] ");
  if (bracket != std::string::npos) what = what.substr(bracket + 2);
  if (const auto colon = what.find(": "); e.id == 101 && colon != std::string::npos) what = what.substr(colon + 2);
  if (e.id == 406) what += " (numbers must be finite)";
  const std::string where = byte ? " at line " + std::to_string(line) + ", column " + std::to_string(column) : "";
  throw SceneFileError(file, tracker.path(), "malformed JSON" + where + ": " + what);
}

}  // namespace

// parse_strict_json, keeping in `underflows` (when given) the numbers that read as 0 though they are not.
nlohmann::json parse_strict_json(const std::string& text, const std::string& file, NumberTexts* underflows) {
  // nlohmann's parser ends its input at a NUL byte, as a C string ends: whatever followed it was
  // never read, and a scene cut short that way ran as if whole.
  if (const size_t nul = text.find('\0'); nul != std::string::npos) {
    const size_t line_start = text.rfind('\n', nul) + 1;  // (npos + 1 = 0: the first line)
    const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(nul), '\n');
    throw SceneFileError(file, "", "malformed JSON at line " + std::to_string(line) + ", column " +
                                       std::to_string(nul - line_start + 1) + ": a NUL byte (a text file has none)");
  }
  {
    FieldPathTracker checker;  // duplicate keys and deep nesting, before the document is built
    checker.keep_underflows(underflows);
    if (!nlohmann::json::sax_parse(text, &checker) && !checker.problem().empty())
      throw SceneFileError(file, checker.path(), checker.problem());
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw_parse_error(text, file, e, e.byte);
  } catch (const nlohmann::json::exception& e) {  // e.g. 1e999: number overflow
    throw_parse_error(text, file, e, 0);
  }
}

nlohmann::json parse_strict_json(const std::string& text, const std::string& file) {
  return parse_strict_json(text, file, nullptr);
}

}  // namespace motus
