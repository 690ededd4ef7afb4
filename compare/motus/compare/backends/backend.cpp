#include "motus/compare/backends/backend.hpp"

#include "motus/compare/backends/box2d_backend.hpp"
#include "motus/compare/backends/bullet_backend.hpp"
#include "motus/compare/backends/motus_backend.hpp"

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

std::vector<std::string> backend_names() {
  return {"motus", "box2d", "bullet"};
}

std::unique_ptr<Backend> make_backend(const std::string& name) {
  if (name == "motus") return std::make_unique<MotusBackend>();
  if (name == "box2d") return std::make_unique<Box2dBackend>();
  if (name == "bullet") return std::make_unique<BulletBackend>();
  throw std::invalid_argument("unknown engine \"" + name + "\"");
}

}  // namespace motus::compare
