#include "option_values.hpp"

#include <cctype>
#include <charconv>
#include <optional>
#include <system_error>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "output_files.hpp"

namespace motus::cli {

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

}  // namespace motus::cli
