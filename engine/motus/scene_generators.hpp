#pragma once
// Scene generators: the many bodies and sticks of a cloth or a rope, appended to a
// mechanical scene (the course's fabric-and-ragdoll demo). A scene file names them as
// "cloth": {...} and "rope": {...} objects with exactly these fields.
#include <array>
#include <string>

#include "motus/scene.hpp"

namespace motus {

// A rows × columns grid of point masses, from `origin` (its top-left corner). In the
// "xy" plane it hangs: column c, row r sits at origin + (c·spacing, −r·spacing, 0). In
// the "xz" plane (3-D scenes) it lies flat: origin + (c·spacing, 0, r·spacing), and
// falls, held by its pins (`pin`), into a drape. Structural
// sticks join horizontal and vertical neighbours; shear sticks (both diagonals of every
// square) keep the squares from folding flat. Every rest length is the initial distance.
struct ClothGenerator {
  int rows = 10, columns = 10;
  double spacing = 0.1;  // m between neighbours
  double mass = 0.01;    // kg per particle
  std::array<double, 3> origin{0, 0, 0};
  bool shear = true;
  std::string pin = "top-corners";  // "top-corners", "top-row" or "none"
  std::string plane = "xy";         // "xy" (hanging) or "xz" (lying flat; 3-D only)
};

// segments + 1 point masses on a straight line from `origin` along `direction`, joined
// by sticks of segment_length; the first one pinned where it starts (with pin_first).
struct RopeGenerator {
  int segments = 20;
  double segment_length = 0.1;  // m
  double mass = 0.01;           // kg per particle
  std::array<double, 3> origin{0, 0, 0};
  std::array<double, 3> direction{1, 0, 0};  // need not be a unit vector
  bool pin_first = true;
};

// Append the bodies, sticks and pins; body indices continue after the scene's bodies.
// Throw SceneError naming the field ("cloth.rows", "rope.direction", ...) for bad values.
void add_cloth(MechanicalDescription& scene, const ClothGenerator& cloth);
void add_rope(MechanicalDescription& scene, const RopeGenerator& rope);

}  // namespace motus
