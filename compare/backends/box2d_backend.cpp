#include "box2d_backend.hpp"

namespace motus::compare {

struct Box2dBackend::World {};
Box2dBackend::Box2dBackend() = default;
Box2dBackend::~Box2dBackend() = default;
std::string Box2dBackend::version() const { return "stub"; }
void Box2dBackend::build(const SceneDescription&, Integrator, double) { throw Unsupported("box2d", {"everything (not written yet)"}); }
void Box2dBackend::step() {}
void Box2dBackend::read(Snapshot&) const {}
std::vector<std::string> Box2dBackend::settings() const { return {}; }
std::vector<std::string> Box2dBackend::notes() const { return {}; }

}  // namespace motus::compare
