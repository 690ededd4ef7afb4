#pragma once
// The order in which a sweep visits the sticks, as groups of sticks that share no body.
//
// A sweep is Gauss–Seidel: each stick sees the positions the sticks before it left. Sticks that
// share no body do not see each other, so within a group the processor overlaps them (and two go
// into one SIMD register); in the scene's order consecutive sticks often share a body (a cloth's
// generator lists three sticks per particle in a row), each must wait for the one before it, and
// the sweep runs at the latency of a square root and a division per stick. Two orders:
//
//   scene    levels: a stick's level is one more than the highest level of the sticks before it
//            (in the scene's order) that share one of its bodies. Every stick still runs after
//            exactly the earlier sticks it depends on, so a sweep level by level gives the scene's
//            order's numbers to the last bit (a Gauss–Seidel sweep's wavefront). A chain is one
//            stick per level; a 20 × 20 cloth with both diagonals has 1,482 sticks in 167 levels.
//   colours  a greedy edge colouring: each stick takes the smallest colour neither of its bodies
//            has yet (at most 2k − 1 colours for bodies of k sticks; the cloth takes 8). A
//            different Gauss–Seidel order, without the scene order's direction: what substeps
//            need (docs/course.md, section 10; Fratarcangeli & Pellacini 2015 colour for speed).
#include <vector>

#include "motus/constrain/constraints.hpp"

namespace motus {

enum class SweepOrder { scene, colours };

struct StickGroups {
  std::vector<int> order;        // indices into the sticks, group by group, in the scene's order within a group
  std::vector<int> group_start;  // group g: order[group_start[g] .. group_start[g + 1])
  int groups() const { return static_cast<int>(group_start.size()) - 1; }
};

// `bodies` is the number of bodies the sticks' indices refer to.
StickGroups sweep_groups(const std::vector<StickConstraint>& sticks, int bodies, SweepOrder order);

}  // namespace motus
