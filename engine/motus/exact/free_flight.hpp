#pragma once
// "exact": "free-flight" — balls in free flight under one uniform gravity (or none), meeting
// each other and the walls in true, instantaneous collisions, solved event by event.
//
// Between two events every body follows its parabola x(t) = x₀ + v₀ t + ½ g t² exactly. All
// bodies fall alike, so two balls approach along a straight line: they touch when
// |Δx + Δv τ| = r_a + r_b, a quadratic in τ. A ball meets a wall when its height above the
// wall, h₀ + (n·v) τ + ½ (n·g) τ², comes down to its radius. The earliest event is applied as
// the course's impulse along the line of centres (smooth balls, e = e_a·e_b, or e_ball·e_wall
// for a wall) and the search starts again from there. Contacts at the same instant (Newton's
// cradle) are taken one after another, as motus's own collisions take them.
//
// This is the answer a collision scene should give — the reference `motus compare` and
// `motus bench precision` measure every engine against. It stops (no state) where a ball
// would come to rest on a wall under gravity (the bounces of e < 1 accumulate in finite time)
// or after kFreeFlightMaxEvents events: the solution is then unknown from that time on.
#include <optional>

#include "motus/scene.hpp"
#include "motus/vector.hpp"

namespace motus {

constexpr long kFreeFlightMaxEvents = 100000;
constexpr int kFreeFlightMaxBodies = 64;

// Throws SceneError("exact", ...) unless the scene is this problem: only uniform gravity, walls
// that are planes or boxes, no sticks, pins or springs, at most kFreeFlightMaxBodies bodies, and
// no two balls (nor a ball and a wall) overlapping at the start.
void check_free_flight(const SceneDescription& scene);

// [x; v] at `elapsed` seconds after the start, or nullopt past the time the solution is known.
std::optional<Vector> free_flight_state(const SceneDescription& scene, double elapsed);

}  // namespace motus
