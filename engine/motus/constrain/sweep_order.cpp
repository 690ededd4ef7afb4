#include "motus/constrain/sweep_order.hpp"

#include <algorithm>

namespace motus {

StickGroups sweep_groups(const std::vector<StickConstraint>& sticks, int bodies, SweepOrder order) {
  const auto n = static_cast<size_t>(std::max(bodies, 0));
  std::vector<int> group(sticks.size());
  int groups = 0;
  if (order == SweepOrder::scene) {
    std::vector<int> last(n, -1);  // the level of the latest stick so far at each body
    for (size_t s = 0; s < sticks.size(); ++s) {
      const auto a = static_cast<size_t>(sticks[s].a), b = static_cast<size_t>(sticks[s].b);
      group[s] = std::max(last[a], last[b]) + 1;
      last[a] = last[b] = group[s];
      groups = std::max(groups, group[s] + 1);
    }
  } else {
    std::vector<std::vector<int>> used(n);  // the colours already at each body (a few each)
    auto taken = [&](int body, int c) {
      const auto& u = used[static_cast<size_t>(body)];
      return std::find(u.begin(), u.end(), c) != u.end();
    };
    for (size_t s = 0; s < sticks.size(); ++s) {
      int c = 0;
      while (taken(sticks[s].a, c) || taken(sticks[s].b, c)) ++c;
      group[s] = c;
      used[static_cast<size_t>(sticks[s].a)].push_back(c);
      used[static_cast<size_t>(sticks[s].b)].push_back(c);
      groups = std::max(groups, c + 1);
    }
  }
  StickGroups result;
  result.group_start.assign(static_cast<size_t>(groups) + 1, 0);
  for (int g : group) ++result.group_start[static_cast<size_t>(g) + 1];
  for (size_t g = 0; g < static_cast<size_t>(groups); ++g) result.group_start[g + 1] += result.group_start[g];
  result.order.resize(sticks.size());
  std::vector<int> next(result.group_start.begin(), result.group_start.end() - 1);
  for (size_t s = 0; s < sticks.size(); ++s)
    result.order[static_cast<size_t>(next[static_cast<size_t>(group[s])]++)] = static_cast<int>(s);
  return result;
}

}  // namespace motus
