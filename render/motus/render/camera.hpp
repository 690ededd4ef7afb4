#pragma once
// Cameras: orthographic for 1-D and 2-D scenes, perspective for 3-D ones, and the
// formula that takes a world point to a pixel (what the tests check a ball against).
#include <array>

#include "motus/render/image.hpp"

namespace motus::render {

using Vec3 = std::array<double, 3>;

struct Camera {
  enum class Projection { orthographic, perspective };
  Projection projection = Projection::orthographic;

  // Orthographic: world point (center_x, center_y) at the viewport's centre, `scale`
  // pixels per metre, world y up.
  double center_x = 0, center_y = 0, scale = 1;

  // Perspective: a pinhole at `eye` looking at `target`, vertical field of view fov_y.
  Vec3 eye{0, 0, 10}, target{0, 0, 0}, up{0, 1, 0};
  double fov_y_degrees = 40, near = 0.05, far = 1000;

  static Camera orthographic(double center_x, double center_y, double scale);
  static Camera perspective(Vec3 eye, Vec3 target, Vec3 up, double fov_y_degrees);
  bool is_perspective() const { return projection == Projection::perspective; }
};

// Where world point p lands in canvas pixels (x to the right, y down; pixel (i, j)
// covers [i, i+1) × [j, j+1), so its centre is at (i + ½, j + ½)); [2] is the depth
// along the view direction (0 for orthographic).
//   orthographic: px = v.x + v.width/2 + (p.x − center_x)·scale
//                 py = v.y + v.height/2 − (p.y − center_y)·scale
//   perspective:  with the camera frame f = (target − eye)/|…|, r = f × up/|…|, u = r × f,
//                 d = p − eye, k = (v.height/2) / tan(fov_y/2):
//                 px = v.x + v.width/2 + k (d·r)/(d·f),  py = v.y + v.height/2 − k (d·u)/(d·f)
Vec3 project(const Camera& camera, const Viewport& viewport, const Vec3& p);

// Column-major 4 × 4 matrices for glLoadMatrixd (perspective cameras): the same
// projection as project(), in the viewport's normalised device coordinates.
std::array<double, 16> projection_matrix(const Camera& camera, const Viewport& viewport);
std::array<double, 16> view_matrix(const Camera& camera);

}  // namespace motus::render
