#pragma once
// What an error message may echo of what the user wrote (a scene file's string, a path, a --set
// value): one line of at most `limit` bytes, shortened in its middle and never inside a UTF-8
// sequence, with bytes that are not UTF-8 shown as '?' and line breaks as spaces — a 50 MB string
// or a file name of raw bytes is no message.
#include <string>

namespace motus {

std::string one_printable_line(const std::string& text, size_t limit);

}  // namespace motus
