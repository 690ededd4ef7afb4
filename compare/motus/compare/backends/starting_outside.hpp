#pragma once
// Bodies that start on the wrong side of a wall. motus moves such a body onto the plane (or
// into the box) before the first step; a peer's wall would keep it where it is, or push it out
// with energy it did not have (Bullet), so the peers refuse the scene rather than run another.
#include <functional>
#include <string>
#include <vector>

#include "motus/scene.hpp"

namespace motus::compare {

// "body I starting outside plane J" (or box J): the first such body of each wall. `start(i, k)`
// is body i's coordinate k at the start (a pinned body's: its pin), in the scene's d dimensions.
std::vector<std::string> bodies_starting_outside(const MechanicalDescription& m,
                                                 const std::function<double(size_t, int)>& start);

}  // namespace motus::compare
