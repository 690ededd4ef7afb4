#pragma once
// Bodies that start where motus will not leave them. One on the wrong side of a wall: motus moves
// it onto the plane (or into the box) before the first step; a peer's wall would keep it where it
// is, or push it out with energy it did not have (Bullet). One pinned away from where it starts:
// motus jumps it to the pin at the first step; a peer's body is made at the pin, so the two start
// from different states (and energies). The peers refuse such scenes rather than run others.
#include <string>
#include <vector>

#include "motus/scene.hpp"

namespace motus::compare {

// "body I starting outside plane J" (or box J): the first such body of each wall. (A pinned body
// starts at its pin, unless bodies_pinned_away names it.)
std::vector<std::string> bodies_starting_outside(const MechanicalDescription& m);

// "body I pinned away from where it starts": the first such pin.
std::vector<std::string> bodies_pinned_away(const MechanicalDescription& m);

}  // namespace motus::compare
