#include "motus/scene_file/printable_text.hpp"

#include "motus/scene_file/scene_overrides.hpp"

namespace motus {

std::string one_printable_line(const std::string& text, size_t limit) {
  std::string line;
  for (size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    const size_t length = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    if (length > 1 && i + length <= text.size() && valid_utf8(text.substr(i, length))) {
      line.append(text, i, length);
      i += length;
    } else {
      line += length == 1 ? (c == '\n' || c == '\r' ? ' ' : text[i]) : '?';
      ++i;
    }
  }
  if (line.size() <= limit) return line;
  auto boundary = [&](size_t i) {
    while (i > 0 && i < line.size() && (static_cast<unsigned char>(line[i]) & 0xC0) == 0x80) --i;
    return i;
  };
  const size_t head = boundary(limit / 2), tail = boundary(line.size() - limit / 2 + 3);
  return line.substr(0, head) + "…" + line.substr(tail);
}

}  // namespace motus
