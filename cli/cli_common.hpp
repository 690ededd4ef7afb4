#pragma once
// What every `motus` subcommand shares: the exit codes, a message on standard error that never
// throws, and the one-line error for input that cannot be used.
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "motus/scene_error.hpp"

namespace motus::cli {

// Exit codes: 0 done; 1 the run itself failed; 2 bad input (scene, option or file).
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

// A message for the user on standard error, as fmt::print(stderr, …) prints it, but never
// throwing. With standard error closed or full (2>&-, 2>/dev/full) fmt::print throws, and the
// handler that then prints the error threw again: motus aborted (exit 134) instead of exiting 1
// or 2. What cannot be written is lost; the exit status still says what happened.
template <typename... Args>
void tell(fmt::format_string<Args...> format, Args&&... args) noexcept {
  try {
    const std::string text = fmt::format(format, std::forward<Args>(args)...);
    if (std::fwrite(text.data(), 1, text.size(), stderr) != text.size()) std::clearerr(stderr);
  } catch (...) {
  }
}

// Bad input that is not inside a scene file (an option, an output path): exit 2.
class InputError : public std::runtime_error {
public:
  explicit InputError(const std::string& message) : std::runtime_error(without_nul(message)) {}  // (scene_error.hpp)
};

// An error message as one line of at most `limit` bytes (shortened in the middle, bytes that are
// not UTF-8 as '?'): messages echo what the user gave, which may be long, have line breaks or be a
// file name of raw bytes.
std::string one_line(const std::string& text, size_t limit = 400);

}  // namespace motus::cli
