#include "help_format.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <sstream>

namespace motus::cli {

size_t help_width() {
  winsize size{};
  if (isatty(STDOUT_FILENO) && ioctl(STDOUT_FILENO, TIOCGWINSZ, &size) == 0 && size.ws_col > 0)
    return std::max<size_t>(60, size.ws_col);
  return 100;
}

std::string wrap_words(const std::string& text, size_t width) {
  std::string out;
  std::istringstream lines(text);
  bool first_line = true;
  for (std::string line; std::getline(lines, line);) {
    if (!first_line) out += '\n';
    first_line = false;
    size_t used = 0;
    std::istringstream words(line);
    for (std::string word; words >> word;) {
      // (Counted in characters, not bytes: "…" and "×" are one column each.)
      const size_t columns = static_cast<size_t>(std::count_if(word.begin(), word.end(), [](char c) {
        return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
      }));
      if (used > 0 && used + 1 + columns > width) out += '\n', used = 0;
      if (used > 0) out += ' ', ++used;
      out += word;
      used += columns;
    }
  }
  return out;
}

WrappingFormatter::WrappingFormatter(size_t width) : width_(width) {}

std::string WrappingFormatter::wrapped(const std::string& text) const {
  // The description starts at the name column's end (format_help indents each line break to it).
  const size_t column = get_column_width();
  return wrap_words(text, width_ > column + 20 ? width_ - column : 20);
}

std::string WrappingFormatter::make_option_desc(const CLI::Option* option) const {
  return wrapped(CLI::Formatter::make_option_desc(option));
}

std::string WrappingFormatter::make_description(const CLI::App* app) const {
  const std::string description = CLI::Formatter::make_description(app);
  return description.empty() ? description : wrap_words(description, width_) + "\n";
}

std::string WrappingFormatter::make_subcommand(const CLI::App* sub) const {
  std::stringstream out;
  CLI::detail::format_help(out, sub->get_display_name(true), wrapped(sub->get_description()), get_column_width());
  return out.str();
}

}  // namespace motus::cli
