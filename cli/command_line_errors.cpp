#include "command_line_errors.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <sstream>

#include "cli_common.hpp"
#include "motus/scene_file/spelling.hpp"

namespace motus::cli {
namespace {

// The commands a user can name at this level (the hidden ones — serve — are not suggested).
std::vector<std::string> command_names(const CLI::App& at, bool hidden_too) {
  std::vector<std::string> names;
  for (const CLI::App* c : at.get_subcommands([](const CLI::App*) { return true; }))
    if (hidden_too || !c->get_group().empty()) names.push_back(c->get_name());
  return names;
}

// Every spelling of every option of `at`: "--dt", "-h", ...
std::vector<std::string> option_names(const CLI::App& at) {
  std::vector<std::string> names;
  for (const CLI::Option* o : at.get_options()) {
    for (const auto& l : o->get_lnames()) names.push_back("--" + l);
    for (const auto& s : o->get_snames()) names.push_back("-" + s);
  }
  return names;
}

// The command the parse had reached ("run", "bench precision"), and its App.
const CLI::App* reached(const CLI::App& app, std::string* path) {
  const CLI::App* at = &app;
  for (;;) {
    const auto parsed = at->get_subcommands();
    if (parsed.empty()) return at;
    at = parsed.front();
    *path += (path->empty() ? "" : " ") + at->get_name();
  }
}

std::string help_for(const std::string& path) { return "(motus " + (path.empty() ? "" : path + " ") + "--help)"; }

const CLI::Option* option_named(const CLI::App& at, const std::string& name) {
  for (const CLI::Option* o : at.get_options())
    if (o->check_name(name) || o->get_name() == name) return o;
  return nullptr;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

std::optional<std::string> word_after_help(const CLI::App& app, const std::vector<std::string>& words) {
  const CLI::App* at = &app;
  std::string path;
  for (const std::string& word : words) {
    const auto names = command_names(*at, true);
    if (std::find(names.begin(), names.end(), word) == names.end()) {
      // (Not a command where one belongs — motus help rnu, motus help bench precison: misplaced_word
      // says which one was meant.)
      if (at->get_require_subcommand_min() > 0) return std::nullopt;
      return "help: \"" + one_line(word, 80) + "\" is not a command of motus " + path + " (motus help " + path + ")";
    }
    at = at->get_subcommand(word);
    path += (path.empty() ? "" : " ") + word;
  }
  return std::nullopt;
}

std::optional<std::string> misplaced_word(const CLI::App& app, const std::vector<std::string>& args) {
  const CLI::App* at = &app;
  std::string path;
  for (const std::string& word : args) {
    if (starts_with(word, "-")) {
      // Before any command only --help, -h and --version are options.
      if (at != &app) return std::nullopt;
      const std::string name = word.substr(0, word.find('='));
      if (option_named(app, name)) return std::nullopt;
      return "unknown option " + one_line(name, 80) + did_you_mean(name, option_names(app)) +
             " (a command's options come after it: motus COMMAND --help)";
    }
    const auto names = command_names(*at, true);
    if (std::find(names.begin(), names.end(), word) == names.end()) {
      if (at->get_require_subcommand_min() == 0) return std::nullopt;  // a command's own argument (a scene)
      const auto shown = command_names(*at, false);
      return (path.empty() ? "" : path + ": ") + "unknown command \"" + one_line(word, 80) + "\"" +
             did_you_mean(word, shown) + " (the commands: " + fmt::format("{}", fmt::join(shown, ", ")) + "; " + help_for(path).substr(1);
    }
    at = at->get_subcommand(word);
    path += (path.empty() ? "" : " ") + word;
    if (at->get_require_subcommand_min() == 0) return std::nullopt;  // from here on, the command's arguments
  }
  return std::nullopt;
}

std::string parse_error_line(const CLI::App& app, const CLI::ParseError& e) {
  std::string path;
  const CLI::App* at = reached(app, &path);
  const std::string help = help_for(path);
  const std::string what = e.what();

  // An option the command does not have (or a word more than it takes) is named first: it is
  // often why something else seems missing ("render spring --ot x": --out is required).
  // Every word after "--" is an argument however it is spelt ("motus run -- -odd-name.json"): one
  // left over there is a word too many, not an option ("run -- x.json --repeats 1").
  const std::vector<std::string> extras = app.remaining(true);
  for (const std::string& word : extras) {
    if (word == "--") {
      const auto next = std::find(extras.begin(), extras.end(), word) + 1;
      if (next == extras.end()) break;
      return "unexpected argument \"" + one_line(*next, 80) + "\" after --, where every word is an argument (options go before --) " +
             help;
    }
    if (starts_with(word, "-") && word.size() > 1) {
      const std::string name = word.substr(0, word.find('='));
      return "unknown option " + one_line(name, 80) + did_you_mean(name, option_names(*at)) + " " + help;
    }
  }
  // An option given no value took the next option as it ("run x --integrator --steps 20": CLI11 gives
  // --integrator "--steps", and "20" is then a word too many, which was all the error said).
  if (!extras.empty())
    for (const CLI::Option* o : at->get_options()) {
      if (o->get_lnames().empty()) continue;
      for (const std::string& value : o->results())
        if (starts_with(value, "-") && value.size() > 1 && option_named(*at, value.substr(0, value.find('='))))
          return "--" + o->get_lnames().front() + ": needs a value; the option " + one_line(value, 80) +
                 " after it was taken as one " + help;
    }
  if (dynamic_cast<const CLI::ExtrasError*>(&e) && !extras.empty())
    return "unexpected argument \"" + one_line(extras.front(), 80) + "\" " + help;
  // "Could not convert: --dt = abc"
  if (dynamic_cast<const CLI::ConversionError*>(&e) && starts_with(what, "Could not convert: ")) {
    const std::string rest = what.substr(19);
    const size_t eq = rest.find(" = ");
    if (eq != std::string::npos) {
      const std::string name = rest.substr(0, eq), value = rest.substr(eq + 3);
      const CLI::Option* o = option_named(*at, name);
      const std::string type = o ? o->get_type_name() : "";
      const std::string expected = starts_with(type, "INT")     ? "a whole number"
                                   : starts_with(type, "FLOAT") ? "a number"
                                                                : "a value of its kind";
      return name + ": \"" + one_line(value, 80) + "\" is not " + expected + " " + help;
    }
  }
  // "--video: mp5 not in {mp4,gif}" (a choice among words)
  if (dynamic_cast<const CLI::ValidationError*>(&e)) {
    const size_t colon = what.find(": "), not_in = what.find(" not in {");
    if (colon != std::string::npos && not_in != std::string::npos && not_in > colon && what.back() == '}') {
      const std::string name = what.substr(0, colon), value = what.substr(colon + 2, not_in - colon - 2);
      std::vector<std::string> choices;  // (CLI11's set, "{mp4,gif}")
      std::istringstream set(what.substr(not_in + 9, what.size() - not_in - 10));
      for (std::string choice; std::getline(set, choice, ',');) choices.push_back(choice);
      return name + ": \"" + one_line(value, 80) + "\" is none of " + fmt::format("{}", fmt::join(choices, ", ")) +
             did_you_mean(value, choices) + " " + help;
    }
  }
  // "--dt: At Most 1 required but received 2"
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) {
    const size_t colon = what.find(": At Most 1 required");
    if (colon != std::string::npos) return what.substr(0, colon) + ": given more than once " + help;
  }
  // "--duration excludes --steps", "--fps requires --render"
  if (dynamic_cast<const CLI::ExcludesError*>(&e)) {
    const size_t word = what.find(" excludes ");
    if (word != std::string::npos)
      return what.substr(0, word) + " and " + what.substr(word + 10) + " cannot be given together " + help;
  }
  if (dynamic_cast<const CLI::RequiresError*>(&e)) {
    const size_t word = what.find(" requires ");
    if (word != std::string::npos) return what.substr(0, word) + ": only with " + what.substr(word + 10) + " " + help;
  }
  // "scene is required", "--out is required", "A subcommand is required"
  if (dynamic_cast<const CLI::RequiredError*>(&e)) {
    if (starts_with(what, "A subcommand is required"))
      return (path.empty() ? "" : path + ": ") + "a command is needed (the commands: " +
             fmt::format("{}", fmt::join(command_names(*at, false), ", ")) + "; " + help.substr(1);
    const size_t is = what.find(" is required");
    if (is != std::string::npos && what.find(' ') == is) {
      std::string name = what.substr(0, is);
      // (A positional argument is shown as its help shows it: SCENE.)
      if (!starts_with(name, "-"))
        std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return std::toupper(c); });
      return name + " is missing " + help;
    }
  }
  return one_line(what) + " " + help;
}

}  // namespace motus::cli
