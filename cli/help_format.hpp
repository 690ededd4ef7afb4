#pragma once
// `--help` that fits the terminal: CLI11 prints each option's description on one line (up to 275
// characters in motus's), which a terminal breaks anywhere. This formatter wraps descriptions at
// word boundaries, under their column, to the terminal's width (100 columns when standard output
// is no terminal, so that piped help reads the same on every machine).
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

namespace motus::cli {

class WrappingFormatter : public CLI::Formatter {
public:
  explicit WrappingFormatter(size_t width);
  std::string make_option_desc(const CLI::Option* option) const override;
  std::string make_subcommand(const CLI::App* sub) const override;
  std::string make_description(const CLI::App* app) const override;

private:
  std::string wrapped(const std::string& text) const;
  size_t width_;
};

// The width help is wrapped to: the terminal's (at least 60), or 100 when standard output is no terminal.
size_t help_width();

// `text` broken into lines of at most `width` characters at spaces (a longer word stays whole),
// its own line breaks kept.
std::string wrap_words(const std::string& text, size_t width);

}  // namespace motus::cli
