#include "motus/scene_generators.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "motus/scene_error.hpp"

namespace motus {
namespace {

int add_particle(MechanicalDescription& scene, double mass, const std::array<double, 3>& position) {
  BodyDescription b;
  b.mass = mass;
  b.position.assign(position.begin(), position.begin() + scene.dimensions);
  b.velocity.assign(static_cast<size_t>(scene.dimensions), 0.0);
  scene.bodies.push_back(std::move(b));
  return static_cast<int>(scene.bodies.size()) - 1;
}

// The rest length is where the two bodies start: a generated shape starts unstressed.
void add_stick(MechanicalDescription& scene, int a, int b) {
  double length2 = 0;
  for (int k = 0; k < scene.dimensions; ++k) {
    const double d = scene.bodies[b].position[k] - scene.bodies[a].position[k];
    length2 += d * d;
  }
  scene.sticks.push_back({a, b, std::sqrt(length2)});
}

void add_pin(MechanicalDescription& scene, int body) {
  PinConstraint p;
  p.body = body;
  for (int k = 0; k < scene.dimensions; ++k) p.position[k] = scene.bodies[body].position[k];
  scene.pins.push_back(p);
}

}  // namespace

void add_cloth(MechanicalDescription& scene, const ClothGenerator& cloth) {
  if (scene.dimensions < 2) throw SceneError("cloth", "a cloth hangs in the x–y plane: it needs dimensions 2 or 3");
  if (cloth.plane != "xy" && cloth.plane != "xz")
    throw SceneError("cloth.plane", "unknown \"" + cloth.plane + "\"; use \"xy\" (hanging) or \"xz\" (lying flat)");
  if (cloth.plane == "xz" && scene.dimensions != 3)
    throw SceneError("cloth.plane", "a cloth lying in the x–z plane needs a 3-D scene");
  if (cloth.rows < 1 || cloth.columns < 1 || cloth.rows * static_cast<long>(cloth.columns) < 2)
    throw SceneError("cloth.rows", "a cloth needs rows ≥ 1, columns ≥ 1 and at least two particles (" +
                                       std::to_string(cloth.rows) + " × " + std::to_string(cloth.columns) + " given)");
  if (!(cloth.spacing > 0)) throw SceneError("cloth.spacing", "must be > 0 m");
  if (!(cloth.mass > 0)) throw SceneError("cloth.mass", "must be > 0 kg (per particle)");
  if (cloth.pin != "top-corners" && cloth.pin != "top-row" && cloth.pin != "none")
    throw SceneError("cloth.pin", "unknown \"" + cloth.pin + "\"; use \"top-corners\", \"top-row\" or \"none\"");

  const int first = static_cast<int>(scene.bodies.size());
  auto at = [&](int r, int c) { return first + r * cloth.columns + c; };
  for (int r = 0; r < cloth.rows; ++r)
    for (int c = 0; c < cloth.columns; ++c) {
      std::array<double, 3> p = cloth.origin;
      p[0] += c * cloth.spacing;
      if (cloth.plane == "xy") {
        p[1] -= r * cloth.spacing;
      } else {
        p[2] += r * cloth.spacing;
      }
      add_particle(scene, cloth.mass, p);
    }
  for (int r = 0; r < cloth.rows; ++r)
    for (int c = 0; c < cloth.columns; ++c) {
      if (c + 1 < cloth.columns) add_stick(scene, at(r, c), at(r, c + 1));
      if (r + 1 < cloth.rows) add_stick(scene, at(r, c), at(r + 1, c));
      if (cloth.shear && r + 1 < cloth.rows && c + 1 < cloth.columns) {
        add_stick(scene, at(r, c), at(r + 1, c + 1));
        add_stick(scene, at(r, c + 1), at(r + 1, c));
      }
    }
  if (cloth.pin == "top-row") {
    for (int c = 0; c < cloth.columns; ++c) add_pin(scene, at(0, c));
  } else if (cloth.pin == "top-corners") {
    add_pin(scene, at(0, 0));
    if (cloth.columns > 1) add_pin(scene, at(0, cloth.columns - 1));
  }
}

void add_rope(MechanicalDescription& scene, const RopeGenerator& rope) {
  if (rope.segments < 1) throw SceneError("rope.segments", "must be ≥ 1 (" + std::to_string(rope.segments) + " given)");
  if (!(rope.segment_length > 0)) throw SceneError("rope.segment_length", "must be > 0 m");
  if (!(rope.mass > 0)) throw SceneError("rope.mass", "must be > 0 kg (per particle)");
  // The unit direction, scaled by its largest component first: the squared length of
  // [1e200, 0] overflows, and of [1e-200, 0] is 0, though neither is zero.
  double largest = 0;
  for (int k = 0; k < scene.dimensions; ++k) largest = std::max(largest, std::abs(rope.direction[k]));
  if (!(largest > 0))
    throw SceneError("rope.direction", "must not be zero in the scene's " + std::to_string(scene.dimensions) +
                                           " dimensions; e.g. [1, 0]");
  std::array<double, 3> direction{0, 0, 0};
  double norm = 0;
  for (int k = 0; k < scene.dimensions; ++k) {
    direction[k] = rope.direction[k] / largest;
    norm += direction[k] * direction[k];
  }
  norm = std::sqrt(norm);

  int previous = -1;
  for (int j = 0; j <= rope.segments; ++j) {
    std::array<double, 3> p = rope.origin;
    for (int k = 0; k < 3; ++k) p[k] += j * rope.segment_length * direction[k] / norm;
    const int body = add_particle(scene, rope.mass, p);
    if (previous >= 0) add_stick(scene, previous, body);
    else if (rope.pin_first) add_pin(scene, body);
    previous = body;
  }
}

}  // namespace motus
