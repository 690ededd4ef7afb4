#pragma once
// Chains among the sticks: the parts of a scene whose sticks link bodies one after another,
// with no loop and no branch — a rope, a hanging chain, a pendulum of several links. A
// chain's sticks can be solved all at once (chain_solver.hpp) instead of swept.
#include <vector>

#include "motus/constrain/constraints.hpp"
#include "motus/vector.hpp"

namespace motus {

struct StickChain {
  std::vector<int> bodies;  // in order along the chain: stick j joins bodies[j] and bodies[j + 1]
  std::vector<int> sticks;  // indices into the scene's sticks, in the same order
};

// The chains of at least `min_sticks` sticks: every connected group of sticks in which each
// body has at most two sticks and there is no loop. Sticks between two bodies of inverse
// mass 0 (both pinned) take no part: nothing may move them, and they would link nothing.
std::vector<StickChain> find_stick_chains(const std::vector<StickConstraint>& sticks, const Vector& inverse_mass,
                                          int min_sticks);

}  // namespace motus
