#include "cli_common.hpp"

#include "motus/scene_file/printable_text.hpp"

namespace motus::cli {

std::string one_line(const std::string& text, size_t limit) { return one_printable_line(text, limit); }

}  // namespace motus::cli
