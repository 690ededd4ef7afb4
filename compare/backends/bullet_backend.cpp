#include "bullet_backend.hpp"

namespace motus::compare {

struct BulletBackend::World {};
BulletBackend::BulletBackend() = default;
BulletBackend::~BulletBackend() = default;
std::string BulletBackend::version() const { return "stub"; }
void BulletBackend::build(const SceneDescription&, Integrator, double) { throw Unsupported("bullet", {"everything (not written yet)"}); }
void BulletBackend::step() {}
void BulletBackend::read(Snapshot&) const {}
std::vector<std::string> BulletBackend::settings() const { return {}; }
std::vector<std::string> BulletBackend::notes() const { return {}; }

}  // namespace motus::compare
