#include "motus/render/camera.hpp"

#include <cmath>
#include <numbers>

namespace motus::render {

namespace {

Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 normalized(const Vec3& a) {
  const double n = std::sqrt(dot(a, a));
  return n > 0 ? Vec3{a[0] / n, a[1] / n, a[2] / n} : Vec3{0, 0, 0};
}

struct Frame {
  Vec3 f, r, u;
};
Frame frame_of(const Camera& c) {
  const Vec3 f = normalized(sub(c.target, c.eye));
  const Vec3 r = normalized(cross(f, c.up));
  return {f, r, cross(r, f)};
}

double focal(const Camera& c) { return 1 / std::tan(c.fov_y_degrees * std::numbers::pi / 360); }

}  // namespace

Camera Camera::orthographic(double cx, double cy, double s) {
  Camera c;
  c.projection = Projection::orthographic;
  c.center_x = cx, c.center_y = cy, c.scale = s;
  return c;
}

Camera Camera::perspective(Vec3 eye, Vec3 target, Vec3 up, double fov) {
  Camera c;
  c.projection = Projection::perspective;
  c.eye = eye, c.target = target, c.up = up, c.fov_y_degrees = fov;
  return c;
}

Vec3 project(const Camera& c, const Viewport& v, const Vec3& p) {
  const double cx = v.x + v.width / 2.0, cy = v.y + v.height / 2.0;
  if (!c.is_perspective()) return {cx + (p[0] - c.center_x) * c.scale, cy - (p[1] - c.center_y) * c.scale, 0};
  const Frame fr = frame_of(c);
  const Vec3 d = sub(p, c.eye);
  const double depth = dot(d, fr.f), k = v.height / 2.0 * focal(c);
  return {cx + k * dot(d, fr.r) / depth, cy - k * dot(d, fr.u) / depth, depth};
}

std::array<double, 16> projection_matrix(const Camera& c, const Viewport& v) {
  const double f = focal(c), aspect = static_cast<double>(v.width) / v.height;
  const double n = c.near, fa = c.far;
  return {f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (fa + n) / (n - fa), -1, 0, 0, 2 * fa * n / (n - fa), 0};
}

std::array<double, 16> view_matrix(const Camera& c) {
  const Frame fr = frame_of(c);
  return {fr.r[0], fr.u[0], -fr.f[0], 0,  //
          fr.r[1], fr.u[1], -fr.f[1], 0,  //
          fr.r[2], fr.u[2], -fr.f[2], 0,  //
          -dot(fr.r, c.eye), -dot(fr.u, c.eye), dot(fr.f, c.eye), 1};
}

}  // namespace motus::render
