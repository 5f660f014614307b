#include "core/geometry/primitives.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/geometry/mesh_defects.h"

namespace soiq {

namespace {

// Two triangles for the quad a-b-c-d (in cyclic order).
void add_quad(TriangleMesh& m, int32_t a, int32_t b, int32_t c, int32_t d) {
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

}  // namespace

TriangleMesh uv_sphere(const Vec3& centre_mm, double radius_mm, int rings, int segments) {
  rings = std::max(rings, 2);
  segments = std::max(segments, 3);
  TriangleMesh m;
  const double pi = std::numbers::pi;
  m.vertices_mm.push_back(centre_mm + Vec3{0, 0, radius_mm});  // north pole: index 0
  for (int r = 1; r < rings; ++r) {
    const double theta = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * pi * s / segments;
      m.vertices_mm.push_back(centre_mm + radius_mm * Vec3{std::sin(theta) * std::cos(phi),
                                                           std::sin(theta) * std::sin(phi), std::cos(theta)});
    }
  }
  const int32_t south = int32_t(m.vertices_mm.size());
  m.vertices_mm.push_back(centre_mm + Vec3{0, 0, -radius_mm});
  auto ring_vertex = [segments](int r, int s) { return int32_t(1 + (r - 1) * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) {
    m.triangles.push_back({0, ring_vertex(1, s), ring_vertex(1, s + 1)});
    m.triangles.push_back({south, ring_vertex(rings - 1, s + 1), ring_vertex(rings - 1, s)});
  }
  for (int r = 1; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      add_quad(m, ring_vertex(r, s), ring_vertex(r + 1, s), ring_vertex(r + 1, s + 1), ring_vertex(r, s + 1));
    }
  }
  orient_outward(m);
  return m;
}

TriangleMesh uv_sphere_with_triangles(const Vec3& centre_mm, double radius_mm, int64_t triangles) {
  // 2 * segments * (rings - 1) triangles with segments = 2 * rings: about 4 * rings^2.
  const int rings = std::max(2, int(std::lround(std::sqrt(double(triangles) / 4.0))));
  return uv_sphere(centre_mm, radius_mm, rings, 2 * rings);
}

TriangleMesh torus(const Vec3& centre_mm, double major_radius_mm, double minor_radius_mm, int n_major, int n_minor) {
  n_major = std::max(n_major, 3);
  n_minor = std::max(n_minor, 3);
  TriangleMesh m;
  const double pi = std::numbers::pi;
  for (int a = 0; a < n_major; ++a) {
    const double u = 2 * pi * a / n_major;
    for (int b = 0; b < n_minor; ++b) {
      const double v = 2 * pi * b / n_minor;
      const double rho = major_radius_mm + minor_radius_mm * std::cos(v);
      m.vertices_mm.push_back(centre_mm + Vec3{rho * std::cos(u), rho * std::sin(u), minor_radius_mm * std::sin(v)});
    }
  }
  auto at = [n_major, n_minor](int a, int b) { return int32_t((a % n_major) * n_minor + (b % n_minor)); };
  for (int a = 0; a < n_major; ++a) {
    for (int b = 0; b < n_minor; ++b) add_quad(m, at(a, b), at(a + 1, b), at(a + 1, b + 1), at(a, b + 1));
  }
  orient_outward(m);
  return m;
}

TriangleMesh box(const Vec3& lo, const Vec3& hi) {
  TriangleMesh m;
  for (int c = 0; c < 8; ++c) {
    m.vertices_mm.push_back({(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]});
  }
  // Each face as a quad, counter-clockwise seen from outside.
  add_quad(m, 0, 2, 3, 1);  // z = lo
  add_quad(m, 4, 5, 7, 6);  // z = hi
  add_quad(m, 0, 1, 5, 4);  // y = lo
  add_quad(m, 2, 6, 7, 3);  // y = hi
  add_quad(m, 0, 4, 6, 2);  // x = lo
  add_quad(m, 1, 3, 7, 5);  // x = hi
  orient_outward(m);
  return m;
}

TriangleMesh merge(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m = a;
  const int32_t offset = int32_t(a.vertices_mm.size());
  m.vertices_mm.insert(m.vertices_mm.end(), b.vertices_mm.begin(), b.vertices_mm.end());
  for (const auto& t : b.triangles) m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return m;
}

TriangleMesh flipped(const TriangleMesh& m) {
  TriangleMesh f = m;
  for (auto& t : f.triangles) std::swap(t[1], t[2]);
  return f;
}

Mat3 rotation_about(const Vec3& axis, double angle) {
  const Vec3 u = (1 / norm(axis)) * axis;
  const double c = std::cos(angle), s = std::sin(angle), t = 1 - c;
  const double x = u[0], y = u[1], z = u[2];
  return {{{t * x * x + c, t * x * y - z * s, t * x * z + y * s},
           {t * x * y + z * s, t * y * y + c, t * y * z - x * s},
           {t * x * z - y * s, t * y * z + x * s, t * z * z + c}}};
}

TriangleMesh transformed(TriangleMesh m, const Vec3& scale, const Mat3& r, const Vec3& centre) {
  for (Vec3& v : m.vertices_mm) v = centre + mul(r, Vec3{scale[0] * v[0], scale[1] * v[1], scale[2] * v[2]});
  return m;
}

}  // namespace soiq
