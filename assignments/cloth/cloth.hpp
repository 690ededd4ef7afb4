#pragma once
// The cloth assignment: the functions you write in cloth.cpp. After every Verlet step motus
// calls satisfy_constraints to pull the bodies back onto their sticks, out of the walls and
// onto their pins — Jakobsen's relaxation, which holds a cloth, a rope and a ragdoll together.
// assignments/cloth/README.md has the physics; motus/student/constraints.hpp the types.
#include "motus/student/constraints.hpp"

namespace student {

// One stick between bodies a and b of inverse masses w_a = 1/m_a and w_b = 1/m_b (0: a body
// that must not move): move both ends along the stick so that it has its rest length, each by
// its share of the error — a by w_a/(w_a + w_b) of it, b by w_b/(w_a + w_b) — so that the
// lighter end moves more and the centre of mass stays where it was. If both weights are 0, or
// the two ends are at the same point (no direction to push along), change nothing.
void project_stick(VectorInOut x_a, VectorInOut x_b, double w_a, double w_b, double length);

// A body of radius r at x that is inside a wall (wall.normal·x − wall.offset < r): move it
// along the normal back to the wall's surface (wall.normal·x − wall.offset = r).
void project_wall(VectorInOut x, double r, const Wall& wall);

// Jakobsen's relaxation: constraints.iterations sweeps, each over every stick and then every
// body against every wall; the pinned bodies never move (they are infinitely heavy to their
// sticks) and end exactly on their pins.
void satisfy_constraints(Bodies& bodies, const Constraints& constraints);

}  // namespace student
