#pragma once
// What the position-resolution check (position_resolution.cpp, coarse_resolution) keeps of the scene
// this thread loaded last: the fields its bodies and walls came from, which the scene reader hands it.
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "motus/scene.hpp"

namespace motus {

// Where a mechanical scene's bodies and walls came from: what a message about where they are names
// (a generated body is not bodies[i], a file without "bodies" has none).
struct MechanicalFields {
  size_t listed = 0;  // bodies[0, listed) are the file's own list
  struct Generated {
    size_t first = 0, end = 0;     // its bodies, [first, end)
    std::string name, spacing_key;  // "lattice", "spacing"
    std::array<double, 3> origin{0, 0, 0};
  };
  std::vector<Generated> generated;
  size_t planes_generated = 0, boxes_generated = 0;  // (the lattice's container, before the listed ones)
  std::vector<std::string> plane_paths, box_paths;   // the listed planes' and boxes' paths, "colliders[j]"
};

// Keeps `fields` as the ones of `m`, the mechanical scene this thread loaded last (read_scene calls it),
// for coarse_resolution's messages.
void remember_fields(const MechanicalDescription& m, MechanicalFields fields);

}  // namespace motus
