#pragma once
// How the options' values are read and checked beyond CLI11's own: comma-separated lists, whole
// numbers, numbers with no default, and the paths of files and folders to write.
#include <algorithm>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

namespace motus::cli {

// A comma-separated list option (--engines motus,box2d; repeatable, the lists joined).
// CLI11's own splitting drops empty items, so "motus,,box2d" would quietly run two engines:
// here an empty item, like a value that is not a T, is a parse error (one line, exit 2).
template <class T>
CLI::Option* add_list_option(CLI::App* command, const std::string& name, std::vector<T>& values,
                             const std::string& help) {
  auto* option = command->add_option_function<std::vector<std::string>>(
      name,
      [&values, name](const std::vector<std::string>& given) {
        values.clear();
        for (const std::string& list : given) {
          size_t from = 0;
          for (;;) {
            const size_t comma = std::min(list.find(',', from), list.size());
            const std::string item = list.substr(from, comma - from);
            if (item.empty()) throw CLI::ValidationError(name, "an empty item in \"" + list + "\"");
            T value{};
            if (!CLI::detail::lexical_cast(item, value))
              throw CLI::ValidationError(name, "\"" + item + "\" is not a " + std::string(CLI::detail::type_name<T>()));
            values.push_back(std::move(value));
            if (comma == list.size()) break;
            from = comma + 1;
          }
        }
      },
      help);
  option->type_name(std::string(CLI::detail::type_name<T>()) + ",...")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  return option;
}

// For the options that name a file or folder to write: an empty one is refused, not taken for
// "not given" (which would write nothing, or somewhere else, and say nothing).
// A folder to be made: not empty, and not ending in "." or ".." ("new/." ran the whole job, then
// failed to move the finished folder into place and left it under a hidden name).
CLI::Validator folder_path(const std::string& what = "folder");
const CLI::Validator& non_empty_path();

// For the options that count (steps, repeats, samples, levels): a whole number from `low` to `high`,
// as written. CLI11's Range said "Value 1e4 not in range 100 to 10000000" of a number inside the
// range that is not whole; this says what is wrong: "must be a whole number from 100 to 10000000
// (got 1e4)". Added with ->transform(): it passes the number on in plain decimal, as it read it
// (CLI11 reads a leading 0 as octal: --steps 010 ran 8 steps).
CLI::Validator whole_number_in(long low, long high);
// For a whole-number option checked after parsing (--memory-limit, --jobs): a leading 0 read as
// decimal, not octal; anything else left for CLI11's conversion to refuse. With ->transform().
CLI::Validator read_as_decimal();
// For a number option with no default (--dt, --duration, --rtol, --atol), with ->transform(): the
// blanks around it dropped, and an empty value refused. CLI11 reads "" into an empty
// std::optional, and `--dt ''` ran at the scene's dt, exit 0.
CLI::Validator a_number();

}  // namespace motus::cli
