#pragma once
// Small meshes built in code for the core/io mesh tests.

#include <algorithm>
#include <array>
#include <vector>

#include "core/base/triangle_mesh.h"

namespace soiq::testing_io {

// A closed, outward-oriented box with awkward (non-float-representable) coordinates.
inline TriangleMesh awkward_box() {
  TriangleMesh m;
  const double x[2] = {-12.345678901234567, 3.1000000000000001};
  const double y[2] = {0.10000000000000001, 7.7777777777777777};
  const double z[2] = {-100.00000000000001, -98.123456789012345};
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 2; ++i) m.vertices_mm.push_back({x[i], y[j], z[k]});
    }
  }
  // Vertex v = i + 2j + 4k; two triangles per face, counter-clockwise seen from outside.
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

// Each triangle as its three vertex coordinates, rotated so the smallest comes first (orientation
// kept), the list sorted: equal for two meshes with the same triangles however indexed.
inline std::vector<std::array<Vec3, 3>> canonical_triangles(const TriangleMesh& m) {
  std::vector<std::array<Vec3, 3>> out;
  for (const auto& t : m.triangles) {
    std::array<Vec3, 3> p{m.vertices_mm[t[0]], m.vertices_mm[t[1]], m.vertices_mm[t[2]]};
    const auto first = std::min_element(p.begin(), p.end()) - p.begin();
    std::rotate(p.begin(), p.begin() + first, p.end());
    out.push_back(p);
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace soiq::testing_io
