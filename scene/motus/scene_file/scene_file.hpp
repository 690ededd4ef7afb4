#pragma once
// Scene files: JSON in, a checked SceneDescription out. The format is documented in
// docs/scene-format.md and scene/scene.schema.json.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "motus/scene.hpp"
#include "motus/scene_error.hpp"

namespace motus {

// What a scene may hold (docs/scene-format.md, "Limits"): beyond these a scene is refused
// before it is built, with the limit named.
constexpr long kMaxSceneBytes = 64L << 20;    // a scene file: 64 MB
constexpr int kMaxNesting = 64;               // arrays and objects inside each other
constexpr long kMaxBodies = 1'000'000;        // bodies, listed and generated
constexpr long kMaxSticks = 2'000'000;        // sticks
constexpr long kMaxClothParticles = 250'000;  // a cloth generator's rows × columns (500 × 500)

// A scene file that cannot be used: file, field path and what is wrong, printed as
// one line "FILE: FIELD: MESSAGE" of at most a few hundred characters (a long part is
// shortened in its middle).
class SceneFileError : public std::runtime_error {
public:
  SceneFileError(const std::string& file, const std::string& field, const std::string& message);
  std::string file, field, message;
};

// Positions too coarse for a mechanical scene's moves at step dt (docs/scene-format.md, "Limits"):
// far from the origin doubles are far apart (16 m at 1e17 m), and bodies whose steps are less than
// a thousand times that move by rounding, or not at all. The scene's moves are its bodies' speeds
// times dt, at the start and after the scene's duration under the acceleration a the forces give them
// at the start, had it held (|v| dt and |v + a T| dt: the largest a step makes): a body at rest under
// gravity moves; one at rest that no force pushes does not, nor does a pinned one; and a run of small
// steps from rest, whose first ones move little, is not refused for those. Where the bodies are is the
// farthest one's largest coordinate, or where a wall keeps them if that is farther: on a plane's free
// side when the origin is not on it, inside a box. What is wrong, and the field that puts the bodies
// there (SceneError's field), or nothing. The field is as the file says it when `scene` is the one
// this thread loaded last (load_scene, parse_scene): a generated body's is its generator's origin (when
// that alone is too far) or spacing, a wall's colliders[k]'s offset, min or max; otherwise (a
// description made elsewhere) bodies[i].position or the wall's kind.
// (Mutual gravity is left out of the forces of a scene of more than 4096 bodies: its every pair is
// more work than a check should be.)
//
// And, when the positions pass, positions too coarse for the contacts a step of dt resolves: a
// collision is resolved at its time within the step, the bodies taken back along their moves, so where
// one step takes them (the farthest body's coordinate, as above, plus the scene's largest move) doubles
// must be at most kContactResolution of the smallest ball's radius apart. A scene with contacts (two
// balls, or a ball and a wall) only: a head-on pair of balls of r = 0.5 m at dt = 1e16 s (2 m apart where
// the step took them) left both velocities as they were, exit 0. What is wrong, or nothing; the field to
// blame is dt (or the option that set it).
constexpr double kContactResolution = 1e-3;
struct CoarseResolution {
  std::optional<SceneError> positions;  // too coarse for the moves, and the field that puts the bodies there
  std::optional<std::string> contacts;  // too coarse for the contacts (dt's fault)
};
CoarseResolution coarse_resolution(const SceneDescription& scene, double dt);

// Reads and checks a scene file, after applying `overrides` ("PATH=VALUE", the
// command line's --set) to the JSON exactly as if the file had said them.
SceneDescription load_scene(const std::string& file, const std::vector<std::string>& overrides = {});

// The same, from JSON text already in memory (`file` is only used in messages).
SceneDescription parse_scene(const std::string& text, const std::string& file,
                             const std::vector<std::string>& overrides = {});

}  // namespace motus
