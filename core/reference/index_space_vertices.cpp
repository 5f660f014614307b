#include "core/reference/index_space_vertices.h"

#include <cmath>
#include <string>

namespace soiq {

Result<std::vector<Vec3>> index_space_vertices(const TriangleMesh& mesh, const ImageGeometry& geometry) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, kDefaultMaxVoxels));
  if (mesh.triangles.empty()) return invalid_argument("mesh has no triangles; nothing to voxelize");
  const auto vertex_count = int64_t(mesh.vertices_mm.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int32_t v : mesh.triangles[t]) {
      if (v < 0 || v >= vertex_count) {
        return invalid_argument("mesh triangle " + std::to_string(t) + " uses vertex " + std::to_string(v) +
                                " but the mesh has " + std::to_string(vertex_count) + " vertices");
      }
    }
  }
  std::vector<Vec3> out;
  out.reserve(mesh.vertices_mm.size());
  for (size_t v = 0; v < mesh.vertices_mm.size(); ++v) {
    const Vec3& p = mesh.vertices_mm[v];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      return invalid_argument("mesh vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
    out.push_back(geometry.physical_to_index(p));
  }
  return out;
}

}  // namespace soiq
