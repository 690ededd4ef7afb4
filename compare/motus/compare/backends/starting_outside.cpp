#include "motus/compare/backends/starting_outside.hpp"

namespace motus::compare {

std::vector<std::string> bodies_starting_outside(const MechanicalDescription& m) {
  const int d = m.dimensions;
  auto start = [&](size_t i, int k) { return m.bodies[i].position[static_cast<size_t>(k)]; };
  const size_t n = m.bodies.size();
  std::vector<std::string> outside;
  for (size_t j = 0; j < m.colliders.planes.size(); ++j) {
    const auto& p = m.colliders.planes[j];
    for (size_t i = 0; i < n; ++i) {
      double side = 0;
      for (int k = 0; k < d; ++k) side += p.normal[static_cast<size_t>(k)] * start(i, k);
      if (side < p.offset) {
        outside.push_back("body " + std::to_string(i) + " starting outside plane " + std::to_string(j));
        break;
      }
    }
  }
  for (size_t j = 0; j < m.colliders.boxes.size(); ++j) {
    const auto& b = m.colliders.boxes[j];
    for (size_t i = 0; i < n; ++i) {
      bool in = true;
      for (int k = 0; k < d; ++k) {
        const double x = start(i, k);
        in = in && x >= b.min[static_cast<size_t>(k)] && x <= b.max[static_cast<size_t>(k)];
      }
      if (!in) {
        outside.push_back("body " + std::to_string(i) + " starting outside box " + std::to_string(j));
        break;
      }
    }
  }
  return outside;
}

std::vector<std::string> bodies_pinned_away(const MechanicalDescription& m) {
  for (const auto& p : m.pins) {
    const auto& body = m.bodies[static_cast<size_t>(p.body)];
    for (int k = 0; k < m.dimensions; ++k)
      if (p.position[static_cast<size_t>(k)] != body.position[static_cast<size_t>(k)])
        return {"body " + std::to_string(p.body) + " pinned away from where it starts"};
  }
  return {};
}

}  // namespace motus::compare
