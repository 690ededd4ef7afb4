#include "motus/compare/backends/backend.hpp"

namespace motus::compare {
namespace {

std::string join_elements(const std::string& engine, const std::vector<std::string>& elements) {
  std::string text;  // (appended piece by piece: GCC 12 warns falsely on "literal" + string, PR105651)
  for (const auto& e : elements) {
    if (!text.empty()) text += '\n';
    text += "not supported by ";
    text += engine;
    text += ": ";
    text += e;
  }
  return text;
}

}  // namespace

Unsupported::Unsupported(const std::string& engine, const std::vector<std::string>& elements)
    : std::runtime_error(join_elements(engine, elements)), engine_(engine), elements_(elements) {}

}  // namespace motus::compare
