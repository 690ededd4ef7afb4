#pragma once
// Scene files: JSON in, a checked SceneDescription out. The format is documented in
// docs/scene-format.md and scene/scene.schema.json.
#include <stdexcept>
#include <string>
#include <vector>

#include "motus/scene.hpp"

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

// Reads and checks a scene file, after applying `overrides` ("PATH=VALUE", the
// command line's --set) to the JSON exactly as if the file had said them.
SceneDescription load_scene(const std::string& file, const std::vector<std::string>& overrides = {});

// The same, from JSON text already in memory (`file` is only used in messages).
SceneDescription parse_scene(const std::string& text, const std::string& file,
                             const std::vector<std::string>& overrides = {});

}  // namespace motus
