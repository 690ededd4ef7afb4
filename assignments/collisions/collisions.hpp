#pragma once
// The collisions assignment: the functions you write in collisions.cpp. motus finds which
// bodies can touch and when (its broad phase), moves them to the moment they touch, and then
// asks your functions what happens; assignments/collisions/README.md has the physics.
// Vectors have d = 1, 2 or 3 numbers (the scene's dimensions).
#include "motus/student/student.hpp"

namespace student {

// Two balls of masses m_a and m_b touch; n is the unit normal from a's centre to b's, and
// they are approaching along it ((v_b − v_a)·n < 0). Change v_a and v_b by the impulse
// J = −(1 + e) (v_b − v_a)·n / (1/m_a + 1/m_b) along n:  v_a −= (J/m_a) n,  v_b += (J/m_b) n.
// e = 1 is a true elastic collision; e < 1 loses energy. The velocities across n do not change.
void collide_balls(double m_a, VectorInOut v_a, double m_b, VectorInOut v_b, VectorIn n, double e);

// A ball hits a static wall (a body of infinite mass) whose unit normal n points into the free
// side, moving into it (v·n < 0): its velocity after, with restitution e.
void bounce_off_wall(VectorInOut v, VectorIn n, double e);

// Two balls move on straight lines: a from p_a with velocity v_a, b from p_b with v_b. Return
// the first time t ≥ 0 at which they touch, |p_b − p_a + (v_b − v_a) t| = r_a + r_b; if they
// already touch or overlap and are approaching, 0; if they never touch while approaching,
// +infinity (std::numeric_limits<double>::infinity()). Balls moving apart ((p_b − p_a)·(v_b −
// v_a) ≥ 0) never touch, +infinity, even when they touch or overlap now: ask that first.
double time_of_impact(VectorIn p_a, VectorIn v_a, double r_a, VectorIn p_b, VectorIn v_b, double r_b);

// A ball of radius r moves from p with velocity v, on the free side of the plane n·x = offset
// (unit normal n). Return the first t ≥ 0 at which it touches the plane (n·(p + v t) − offset
// = r); 0 if it already touches and moves into the plane; +infinity if it never reaches it — and
// if it moves away from the plane (n·v ≥ 0), even when it touches it now: ask that first.
double time_of_impact_with_plane(VectorIn p, VectorIn v, double r, VectorIn n, double offset);

}  // namespace student
