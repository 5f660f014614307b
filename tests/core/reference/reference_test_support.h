#pragma once
// Small closed meshes built in code for the reference-method tests, and mask helpers. The meshes are independent of
// core/geometry/primitives (so the oracle's tests do not depend on the code under test). Vertices are welded
// by exact coordinate, so shared edges are shared index pairs; every triangle faces outward.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

#include "core/base/image.h"
#include "core/base/run_length_volume.h"
#include "core/base/triangle_mesh.h"
#include "core/base/vec3.h"

namespace soiq::test {

class MeshBuilder {
 public:
  int32_t vertex(const Vec3& p) {
    auto [it, inserted] = index_.try_emplace(p, int32_t(mesh_.vertices_mm.size()));
    if (inserted) mesh_.vertices_mm.push_back(p);
    return it->second;
  }
  // Adds triangle abc, flipped if needed so that its normal has a positive dot with `outward`.
  void triangle(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& outward) {
    const bool flip = dot(cross(b - a, c - a), outward) < 0;
    mesh_.triangles.push_back({vertex(a), flip ? vertex(c) : vertex(b), flip ? vertex(b) : vertex(c)});
  }
  // Quad p0 p1 p2 p3 (in cyclic order) as two triangles split along p0-p2.
  void quad(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, const Vec3& outward) {
    triangle(p0, p1, p2, outward);
    triangle(p0, p2, p3, outward);
  }
  const TriangleMesh& mesh() const { return mesh_; }

 private:
  TriangleMesh mesh_;
  std::map<Vec3, int32_t> index_;
};

// Axis-aligned box [lo, hi] with every face cut into n x n quads (2 triangles each), so that for
// integer corners and n = hi - lo, lines pass exactly through shared edges and vertices.
inline TriangleMesh tessellated_box(const Vec3& lo, const Vec3& hi, int n = 1) {
  MeshBuilder b;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      Vec3 outward{0, 0, 0};
      outward[axis] = side ? 1 : -1;
      for (int a = 0; a < n; ++a) {
        for (int c = 0; c < n; ++c) {
          auto corner = [&](int da, int dc) {
            Vec3 p{};
            p[axis] = side ? hi[axis] : lo[axis];
            p[u] = lo[u] + (hi[u] - lo[u]) * (a + da) / n;
            p[v] = lo[v] + (hi[v] - lo[v]) * (c + dc) / n;
            return p;
          };
          b.quad(corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1), outward);
        }
      }
    }
  }
  return b.mesh();
}

// The octahedron |x - cx| + |y - cy| + |z - cz| <= r: 8 triangles.
inline TriangleMesh octahedron(const Vec3& centre, double r) {
  MeshBuilder b;
  for (int sx : {-1, 1}) {
    for (int sy : {-1, 1}) {
      for (int sz : {-1, 1}) {
        b.triangle(centre + Vec3{sx * r, 0, 0}, centre + Vec3{0, sy * r, 0}, centre + Vec3{0, 0, sz * r},
                   Vec3{double(sx), double(sy), double(sz)});
      }
    }
  }
  return b.mesh();
}

// A UV sphere inscribed in the sphere (centre, r): `rings` latitude bands, `segments` longitudes.
inline TriangleMesh uv_sphere_mesh(const Vec3& centre, double r, int rings, int segments) {
  MeshBuilder b;
  const double pi = std::acos(-1.0);
  auto point = [&](int ring, int seg) {
    if (ring == 0) return centre + Vec3{0, 0, r};
    if (ring == rings) return centre + Vec3{0, 0, -r};
    const double theta = pi * ring / rings, phi = 2 * pi * (seg % segments) / segments;
    return centre + Vec3{r * std::sin(theta) * std::cos(phi), r * std::sin(theta) * std::sin(phi), r * std::cos(theta)};
  };
  for (int ring = 0; ring < rings; ++ring) {
    for (int seg = 0; seg < segments; ++seg) {
      const Vec3 p00 = point(ring, seg), p01 = point(ring, seg + 1), p10 = point(ring + 1, seg),
                 p11 = point(ring + 1, seg + 1);
      const Vec3 mid = (1.0 / 4) * (p00 + p01 + p10 + p11) - centre;
      if (ring != 0) b.triangle(p00, p01, p11, mid);
      if (ring != rings - 1) b.triangle(p00, p11, p10, mid);
    }
  }
  return b.mesh();
}

// Largest distance between the sphere (centre, r) and the planes of an inscribed mesh's triangles:
// the mesh surface lies within [r - sagitta, r] of the centre.
inline double sagitta(const TriangleMesh& m, const Vec3& centre, double r) {
  double s = 0;
  for (const auto& t : m.triangles) {
    const Vec3 &a = m.vertices_mm[size_t(t[0])], &b = m.vertices_mm[size_t(t[1])], &c = m.vertices_mm[size_t(t[2])];
    const Vec3 n = cross(b - a, c - a);
    s = std::max(s, r - std::abs(dot(n, a - centre)) / norm(n));
  }
  return s;
}

// The boundary faces of a mask's voxels (each a unit square halfway between an inside and an
// outside centre), in LPS mm through the mask's geometry: a closed surface whose voxelization on
// the same grid is the mask itself, with every crossing at a half-integer.
inline TriangleMesh cuberille(const Mask& m) {
  MeshBuilder b;
  const auto& d = m.geometry.dims;
  auto at = [&](int64_t i, int64_t j, int64_t k) {
    if (i < 0 || j < 0 || k < 0 || i >= d[0] || j >= d[1] || k >= d[2]) return false;
    return m.voxels[size_t(i + d[0] * (j + d[1] * k))] != 0;
  };
  for (int64_t k = 0; k < d[2]; ++k) {
    for (int64_t j = 0; j < d[1]; ++j) {
      for (int64_t i = 0; i < d[0]; ++i) {
        if (!at(i, j, k)) continue;
        for (int axis = 0; axis < 3; ++axis) {
          for (int s : {-1, 1}) {
            std::array<int64_t, 3> n{i, j, k};
            n[axis] += s;
            if (at(n[0], n[1], n[2])) continue;
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            auto corner = [&](double du, double dv) {
              Vec3 q{double(i), double(j), double(k)};
              q[axis] += 0.5 * s;
              q[u] += du;
              q[v] += dv;
              return m.geometry.index_to_physical(q);
            };
            Vec3 dir{0, 0, 0};
            dir[axis] = s;
            const Vec3 origin = m.geometry.index_to_physical({0, 0, 0});
            const Vec3 outward = m.geometry.index_to_physical(dir) - origin;
            b.quad(corner(-0.5, -0.5), corner(0.5, -0.5), corner(0.5, 0.5), corner(-0.5, 0.5), outward);
          }
        }
      }
    }
  }
  return b.mesh();
}

// The dense mask of the voxels where `inside(i, j, k)` holds.
inline std::vector<uint8_t> expected_mask(const ImageGeometry& g,
                                          const std::function<bool(int64_t, int64_t, int64_t)>& inside) {
  std::vector<uint8_t> m(size_t(g.voxel_count()));
  for (int64_t k = 0; k < g.dims[2]; ++k)
    for (int64_t j = 0; j < g.dims[1]; ++j)
      for (int64_t i = 0; i < g.dims[0]; ++i) m[size_t(i + g.dims[0] * (j + g.dims[1] * k))] = inside(i, j, k);
  return m;
}

// Number of voxels where `v` and the dense mask `expected` differ.
inline int64_t differing(const RunLengthVolume& v, const std::vector<uint8_t>& expected) {
  const Result<Mask> m = to_mask(v);
  EXPECT_TRUE(m.ok());
  int64_t n = 0;
  for (size_t a = 0; a < expected.size(); ++a) n += m->voxels[a] != expected[a];
  return n;
}

inline bool in(int64_t x, int64_t lo, int64_t hi) { return lo <= x && x < hi; }

inline ImageGeometry cube_grid(int64_t n) {
  ImageGeometry g;
  g.dims = {n, n, n};
  return g;
}

// Two closed meshes as one (a union of components, possibly overlapping).
inline TriangleMesh merged(TriangleMesh a, const TriangleMesh& b) {
  const auto offset = int32_t(a.vertices_mm.size());
  a.vertices_mm.insert(a.vertices_mm.end(), b.vertices_mm.begin(), b.vertices_mm.end());
  for (auto t : b.triangles) a.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return a;
}

}  // namespace soiq::test
