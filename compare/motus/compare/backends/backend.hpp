#pragma once
// One interface for every engine a scene can be run in: build a world from the parsed
// scene, step it, read back every body's position and velocity. The scene description
// is the single source: each backend builds its world from the same SceneDescription.
//
// What a backend cannot express it reports — `not supported by <engine>: <element>` —
// and refuses the scene, rather than run a different scene under the same name.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "motus/integrate/method.hpp"
#include "motus/scene.hpp"

namespace motus::compare {

// Every body's state at one instant, in the scene's order and dimensions (particle i's
// coordinate k at i*d + k). Peers in float or in 3-D are converted to this.
struct Snapshot {
  double t = 0;
  std::vector<double> x, v;
};

// A scene (or part of one) this engine cannot run; what() is one line per element:
// "not supported by box2d: 3-D scenes".
class Unsupported : public std::runtime_error {
public:
  Unsupported(const std::string& engine, const std::vector<std::string>& elements);
  const std::vector<std::string>& elements() const { return elements_; }
  const std::string& engine() const { return engine_; }

private:
  std::string engine_;
  std::vector<std::string> elements_;
};

class Backend {
public:
  virtual ~Backend() = default;

  // "motus", "box2d", "bullet", or a plug-in's name (motus with the plug-in's parts).
  virtual std::string name() const = 0;
  // A line saying which version and precision ("Box2D 2.4.1, float").
  virtual std::string version() const = 0;

  // Builds the world for `scene`, to be stepped with `dt`. motus uses `method`; the
  // peers integrate the way they do (semi-implicit Euler) and ignore it. Throws
  // Unsupported listing every element this engine cannot express.
  virtual void build(const SceneDescription& scene, const Method& method, double dt) = 0;

  // One step of dt (the peers apply the scene's forces through their force API first).
  virtual void step() = 0;

  // The current state.
  virtual void read(Snapshot& out) const = 0;

  // The settings used, one line each, for the report ("velocity iterations: 8").
  virtual std::vector<std::string> settings() const = 0;

  // Where this engine's own limits bite on this scene (Box2D's 2 m per step translation
  // cap, Bullet's angular clamp, ...), one line each; empty when none do.
  virtual std::vector<std::string> notes() const { return {}; }

  // Whether step() watches for what notes() reports (on at first). The timing rounds turn it
  // off, so that a peer's time per step is its engine's alone, not that of our bookkeeping.
  virtual void watch_for_notes(bool /*on*/) {}
};

// The engines compiled in, by name ("motus", "box2d", "bullet").
std::vector<std::string> backend_names();
// Throws std::invalid_argument for an unknown name.
std::unique_ptr<Backend> make_backend(const std::string& name);
// Box2D's and Bullet's ("box2d", "bullet"), which make_backend asks for. motus::compare defines
// it with both peers linked in (peers.cpp); the `motus` command defines its own, which loads them
// from its module motus-peers.so only when a command runs one, so that every other command
// starts without loading Box2D and Bullet. (Its definition is linked before the library's, whose
// peers.cpp is then never taken from the archive.)
std::unique_ptr<Backend> make_peer_backend(const std::string& name);

}  // namespace motus::compare
