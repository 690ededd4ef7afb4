// 3-D mechanical scenes in perspective: lights, lit spheres, the ground grid, box edges, trails
// and cloth as shaded triangles found from its sticks. Separate: depth, lighting and meshes are
// needed only here.
#include <GL/gl.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "motus/render/draw_primitives.hpp"

namespace motus::render::detail {

namespace {

void lights_on() {
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glEnable(GL_NORMALIZE);
  glEnable(GL_COLOR_MATERIAL);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  const GLfloat ambient[] = {0.35f, 0.35f, 0.35f, 1}, diffuse[] = {0.75f, 0.75f, 0.72f, 1},
                specular[] = {0.35f, 0.35f, 0.35f, 1};
  const GLfloat direction[] = {0.35f, 1.0f, 0.55f, 0};  // w = 0: a directional light, in world space
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, ambient);
  glLightfv(GL_LIGHT0, GL_DIFFUSE, diffuse);
  glLightfv(GL_LIGHT0, GL_SPECULAR, specular);
  glLightfv(GL_LIGHT0, GL_POSITION, direction);
  const GLfloat shine[] = {0.3f, 0.3f, 0.3f, 1};
  glMaterialfv(GL_FRONT_AND_BACK, GL_SPECULAR, shine);
  glMaterialf(GL_FRONT_AND_BACK, GL_SHININESS, 40);
}

void lights_off() { glDisable(GL_LIGHTING); }

// A unit sphere as triangle strips (positions double as normals).
struct SphereMesh {
  std::vector<GLfloat> vertices;
  int stacks = 12, slices = 20;
  SphereMesh() {
    for (int i = 0; i < stacks; ++i)
      for (int j = 0; j <= slices; ++j)
        for (int k = 0; k < 2; ++k) {
          const double phi = kPi * (i + k) / stacks, lambda = 2 * kPi * j / slices;
          vertices.push_back(static_cast<GLfloat>(std::sin(phi) * std::cos(lambda)));
          vertices.push_back(static_cast<GLfloat>(std::cos(phi)));
          vertices.push_back(static_cast<GLfloat>(std::sin(phi) * std::sin(lambda)));
        }
  }
  void draw(const Vec3& c, double r) const {
    glPushMatrix();
    glTranslated(c[0], c[1], c[2]);
    glScaled(r, r, r);
    const GLsizei strip = 2 * (slices + 1);
    for (int i = 0; i < stacks; ++i) glDrawArrays(GL_TRIANGLE_STRIP, i * strip, strip);
    glPopMatrix();
  }
};

const SphereMesh& sphere_mesh() {
  static const SphereMesh mesh;
  return mesh;
}

void ground_grid(const Vec3& centre, double half, double y, bool solid) {
  const double step = nice_step(2 * half, 12);
  const double x0 = std::floor((centre[0] - half) / step) * step, z0 = std::floor((centre[2] - half) / step) * step;
  const double x1 = centre[0] + half, z1 = centre[2] + half;
  if (solid) {
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1, 1);
    gl_color(kGround);
    glBegin(GL_QUADS);
    glVertex3d(x0, y, z0);
    glVertex3d(x0, y, z1);
    glVertex3d(x1, y, z1);
    glVertex3d(x1, y, z0);
    glEnd();
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  gl_color(solid ? Color{190, 188, 180, 255} : kGrid);
  glBegin(GL_LINES);
  for (double x = x0; x <= x1 + 1e-9; x += step) glVertex3d(x, y, z0), glVertex3d(x, y, z1);
  for (double z = z0; z <= z1 + 1e-9; z += step) glVertex3d(x0, y, z), glVertex3d(x1, y, z);
  glEnd();
}

void box_edges(const Vec3& a, const Vec3& b) {
  const double xs[2] = {a[0], b[0]}, ys[2] = {a[1], b[1]}, zs[2] = {a[2], b[2]};
  glBegin(GL_LINES);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      glVertex3d(xs[0], ys[i], zs[j]), glVertex3d(xs[1], ys[i], zs[j]);
      glVertex3d(xs[i], ys[0], zs[j]), glVertex3d(xs[i], ys[1], zs[j]);
      glVertex3d(xs[i], ys[j], zs[0]), glVertex3d(xs[i], ys[j], zs[1]);
    }
  glEnd();
}

// Triangles whose three sides are all sticks: a cloth's squares. A square with both
// diagonals (shear sticks) holds four such triangles, two per way of cutting it; only the
// cut along the diagonal from its lowest to its highest body index is kept, so that no
// two triangles overlap. For a triangle a < b < c that means: (a, c) is its longest stick.
std::vector<std::array<int, 3>> stick_triangles(const MechanicalDescription& m) {
  const size_t n = m.bodies.size();
  std::vector<std::vector<std::pair<int, double>>> next(n);  // (neighbour with a larger index, length), sorted
  for (const auto& s : m.sticks) {
    const int a = std::min(s.a, s.b), b = std::max(s.a, s.b);
    next[static_cast<size_t>(a)].push_back({b, s.length});
  }
  for (auto& list : next) std::sort(list.begin(), list.end());
  auto find = [&](int a, int b) -> const std::pair<int, double>* {
    const auto& list = next[static_cast<size_t>(a)];
    const auto it = std::lower_bound(list.begin(), list.end(), std::pair<int, double>{b, -kInf});
    return it != list.end() && it->first == b ? &*it : nullptr;
  };
  std::vector<std::array<int, 3>> triangles;
  for (size_t a = 0; a < n; ++a)
    for (const auto& [b, ab] : next[a])
      for (const auto& [c, bc] : next[static_cast<size_t>(b)])
        if (const auto* ac = find(static_cast<int>(a), c); ac && ac->second >= ab && ac->second >= bc)
          triangles.push_back({static_cast<int>(a), b, c});
  return triangles;
}

}  // namespace

void draw_mechanical_3d(Canvas& canvas, const Viewport& v, const MechanicalDescription& m, const MechanicalFrame& f,
                        const Camera& cam, const DrawOptions& o) {
  const int d = 3, n = static_cast<int>(m.bodies.size());
  begin_3d(canvas, v, cam);
  lights_off();
  glLineWidth(static_cast<GLfloat>(canvas.supersample()));
  if (o.ground_grid) {
    const auto ground = ground_height(m);
    if (o.ground_centre) {
      ground_grid(*o.ground_centre, o.ground_half_width, (*o.ground_centre)[1], ground.has_value());
    } else {
      Box3 b;
      for (int i = 0; i < n; ++i) b.add(point_of(f.positions, d, i), m.bodies[static_cast<size_t>(i)].radius);
      for (const auto& box : m.colliders.boxes) b.add({box.min[0], box.min[1], box.min[2]}), b.add({box.max[0], box.max[1], box.max[2]});
      if (!b.empty()) {
        const Vec3 c = b.centre();
        const double half = std::max({b.hi[0] - b.lo[0], b.hi[2] - b.lo[2], 1e-3}) * 0.9;
        ground_grid(c, half, ground.value_or(b.lo[1]), ground.has_value());
      }
    }
  }
  gl_color(kWall);
  for (const auto& box : m.colliders.boxes) box_edges({box.min[0], box.min[1], box.min[2]}, {box.max[0], box.max[1], box.max[2]});
  if (o.trails && !f.trail.empty() && static_cast<size_t>(n) <= kMostTrailedBodies)
    for (int i = 0; i < n; ++i) {
      gl_color(mix(body_color(i + o.first_body_colour), o.background, 0.4));
      glBegin(GL_LINE_STRIP);
      for (const auto& x : f.trail) {
        const Vec3 p = point_of(x, d, i);
        glVertex3d(p[0], p[1], p[2]);
      }
      glEnd();
    }

  lights_on();
  auto triangles = m.sticks.empty() ? std::vector<std::array<int, 3>>{} : stick_triangles(m);
  if (!triangles.empty()) {
    auto triangle_normal = [](const Vec3& a, const Vec3& b, const Vec3& c) {
      const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      return Vec3{u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    };
    // One winding for the whole sheet, chosen in the scene's initial (flat) layout: every
    // triangle turned to face the same side as the first one. Two-sided lighting then
    // lights the underside as the underside.
    auto initial = [&](int i) {
      const auto& p = m.bodies[static_cast<size_t>(i)].position;
      return Vec3{p[0], p[1], p[2]};
    };
    const Vec3 side = triangle_normal(initial(triangles[0][0]), initial(triangles[0][1]), initial(triangles[0][2]));
    for (auto& t : triangles) {
      const Vec3 n0 = triangle_normal(initial(t[0]), initial(t[1]), initial(t[2]));
      if (n0[0] * side[0] + n0[1] * side[1] + n0[2] * side[2] < 0) t = {t[0], t[2], t[1]};
    }
    // Smooth normals: every triangle adds its normal to its corners.
    std::vector<Vec3> normal(static_cast<size_t>(n), Vec3{0, 0, 0});
    for (const auto& t : triangles) {
      const Vec3 nn = triangle_normal(point_of(f.positions, d, t[0]), point_of(f.positions, d, t[1]),
                                      point_of(f.positions, d, t[2]));
      for (int k : t)
        for (int j = 0; j < 3; ++j) normal[static_cast<size_t>(k)][static_cast<size_t>(j)] += nn[static_cast<size_t>(j)];
    }
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1, 1);
    gl_color({214, 92, 64, 255});
    glBegin(GL_TRIANGLES);
    for (const auto& t : triangles)
      for (int k : t) {
        const Vec3& nn = normal[static_cast<size_t>(k)];
        const Vec3 p = point_of(f.positions, d, k);
        glNormal3d(nn[0], nn[1], nn[2]);
        glVertex3d(p[0], p[1], p[2]);
      }
    glEnd();
    glDisable(GL_POLYGON_OFFSET_FILL);
  } else if (!m.sticks.empty()) {
    lights_off();
    gl_color(kStick);
    glBegin(GL_LINES);
    for (const auto& s : m.sticks) {
      const Vec3 a = point_of(f.positions, d, s.a), b = point_of(f.positions, d, s.b);
      glVertex3d(a[0], a[1], a[2]), glVertex3d(b[0], b[1], b[2]);
    }
    glEnd();
    lights_on();
  }
  // Spheres with one-sided lighting: their normals are right whatever the strips' winding.
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_FALSE);
  const auto& mesh = sphere_mesh();
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_NORMAL_ARRAY);
  glVertexPointer(3, GL_FLOAT, 0, mesh.vertices.data());
  glNormalPointer(GL_FLOAT, 0, mesh.vertices.data());
  Box3 all;
  for (int i = 0; i < n; ++i) all.add(point_of(f.positions, d, i));
  const double dot_radius = std::max(all.radius(), 0.1) * 0.012;
  for (int i = 0; i < n; ++i) {
    const double r = m.bodies[static_cast<size_t>(i)].radius;
    if (r <= 0 && !triangles.empty()) continue;  // the cloth shows them
    gl_color(body_color(i + o.first_body_colour));
    mesh.draw(point_of(f.positions, d, i), r > 0 ? r : dot_radius);
  }
  gl_color({200, 50, 50, 255});
  for (const auto& pin : m.pins) mesh.draw({pin.position[0], pin.position[1], pin.position[2]}, dot_radius * 1.6);
  glDisableClientState(GL_VERTEX_ARRAY);
  glDisableClientState(GL_NORMAL_ARRAY);
  lights_off();
  if (o.velocity_arrows && !f.velocities.empty()) {
    gl_color({200, 40, 40, 255});
    glBegin(GL_LINES);
    for (int i = 0; i < n; ++i) {
      const Vec3 p = point_of(f.positions, d, i), q = point_of(f.velocities, d, i);
      glVertex3d(p[0], p[1], p[2]);
      glVertex3d(p[0] + q[0] * o.arrow_seconds, p[1] + q[1] * o.arrow_seconds, p[2] + q[2] * o.arrow_seconds);
    }
    glEnd();
  }
  glDisable(GL_DEPTH_TEST);
}

}  // namespace motus::render::detail
