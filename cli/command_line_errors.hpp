#pragma once
// The command line's mistakes in motus's words: CLI11's own messages ("The following arguments
// were not expected: 1 --dtt", "A subcommand is required", "Could not convert: --dt = abc") said
// as the rest of motus says an error — `OPTION: what is wrong`, the command named, and the word
// the user most likely meant ("did you mean --dt?").
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace motus::cli {

// Before parsing: a word where a command belongs that is none ("motus rnu", "motus bench
// precison"), or an option before any command that motus does not have ("motus --hlep"), as one
// line (without "motus: error: "), or nothing. (CLI11 says "A subcommand is required" of both, as
// if nothing had been given.)
std::optional<std::string> misplaced_word(const CLI::App& app, const std::vector<std::string>& args);
// `motus help WORDS`: a word after the command it asks about (`motus help run extra`), which its
// --help would pass over in silence. An unknown first word is misplaced_word's to name.
std::optional<std::string> word_after_help(const CLI::App& app, const std::vector<std::string>& words);

// After a failed parse: the error as one line (without "motus: error: "), ending with the help to
// read, `(motus run --help)`.
std::string parse_error_line(const CLI::App& app, const CLI::ParseError& e);

}  // namespace motus::cli
