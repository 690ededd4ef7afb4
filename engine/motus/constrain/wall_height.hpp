#pragma once
// How far a body's surface is out of a wall: the one test the walls' projection (constraint_projection.cpp)
// and their broad phase (near_wall_lists.cpp) share, inline in both (it runs per body and wall).

namespace motus {

// n·x − offset − r: how far body i's surface is out of the wall (< 0: inside it).
template <int D, class Wall>
inline double height_above(const Wall& wall, double r, const double* xi) {
  double height = -wall.offset - r;
  for (int k = 0; k < D; ++k) height += wall.normal[k] * xi[k];
  return height;
}

}  // namespace motus
