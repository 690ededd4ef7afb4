#include "motus/constrain/stick_chains.hpp"

#include <array>
#include <numeric>

namespace motus {

std::vector<StickChain> find_stick_chains(const std::vector<StickConstraint>& sticks, const Vector& inverse_mass,
                                          int min_sticks) {
  const auto n = static_cast<size_t>(inverse_mass.size());
  auto active = [&](const StickConstraint& s) { return inverse_mass[s.a] + inverse_mass[s.b] > 0; };
  // The sticks at each body (only the first two are kept; more makes a branch).
  std::vector<int> degree(n, 0);
  std::vector<std::array<int, 2>> at(n, {-1, -1});
  for (size_t s = 0; s < sticks.size(); ++s) {
    if (!active(sticks[s])) continue;
    for (int body : {sticks[s].a, sticks[s].b}) {
      const auto b = static_cast<size_t>(body);
      if (degree[b] < 2) at[b][static_cast<size_t>(degree[b])] = static_cast<int>(s);
      ++degree[b];
    }
  }
  // Connected groups of bodies (union–find over the active sticks).
  std::vector<size_t> root(n);
  std::iota(root.begin(), root.end(), size_t{0});
  auto find = [&](size_t b) {
    while (root[b] != b) b = root[b] = root[root[b]];
    return b;
  };
  for (const auto& s : sticks)
    if (active(s)) root[find(static_cast<size_t>(s.a))] = find(static_cast<size_t>(s.b));
  std::vector<int> bodies_in(n, 0), sticks_in(n, 0), branching(n, 0);
  for (size_t b = 0; b < n; ++b) {
    if (degree[b] == 0) continue;
    ++bodies_in[find(b)];
    if (degree[b] > 2) branching[find(b)] = 1;
  }
  for (const auto& s : sticks)
    if (active(s)) ++sticks_in[find(static_cast<size_t>(s.a))];

  // A group with no branch and one stick fewer than bodies is a chain: walk it from an end.
  std::vector<StickChain> chains;
  std::vector<char> walked(n, 0);  // each chain has two ends: it is walked from the first one found
  for (size_t b = 0; b < n; ++b) {
    const size_t g = find(b);
    if (degree[b] != 1 || walked[g] || branching[g] || sticks_in[g] != bodies_in[g] - 1 || sticks_in[g] < min_sticks)
      continue;
    walked[g] = 1;
    StickChain chain;
    int body = static_cast<int>(b), previous = -1;
    chain.bodies.push_back(body);
    for (;;) {
      const auto& two = at[static_cast<size_t>(body)];
      const int next = two[0] != previous ? two[0] : two[1];
      if (next < 0) break;  // the other end
      const StickConstraint& s = sticks[static_cast<size_t>(next)];
      body = s.a == body ? s.b : s.a;
      chain.sticks.push_back(next);
      chain.bodies.push_back(body);
      previous = next;
    }
    chains.push_back(std::move(chain));
  }
  return chains;
}

}  // namespace motus
