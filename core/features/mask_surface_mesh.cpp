#include "core/features/mask_surface_mesh.h"

#include <algorithm>
#include <array>
#include <unordered_map>
#include <vector>

namespace soiq {

Result<TriangleMesh> mask_surface_mesh(const RunLengthVolume& volume, const CubeCaseTable& cases, int64_t max_voxels) {
  const ImageGeometry& g = volume.geometry;
  SOIQ_RETURN_IF_ERROR(validate_geometry(g));
  if (int64_t(volume.line_start.size()) != volume.line_count() + 1)
    return invalid_argument("volume's line starts do not match its grid " + describe(g));
  const VoxelBox b = voxel_box(volume);
  if (b.empty) return invalid_argument("the surface of an empty mask is undefined");
  // The box padded by one voxel of outside on every side: cubes reach one voxel beyond the mask.
  VoxelBox padded = b;
  for (size_t a = 0; a < 3; ++a) --padded.lo[a], ++padded.hi[a];
  const std::array<int64_t, 3> lo = padded.lo, n = padded.dims();
  const double voxels = double(n[0]) * double(n[1]) * double(n[2]);
  if (voxels > double(max_voxels))
    return resource_exhausted("the mask's bounding box of " + std::to_string(int64_t(voxels)) +
                              " voxels exceeds the limit of " + std::to_string(max_voxels));
  const std::vector<uint8_t> inside = box_mask(volume, padded);
  auto at = [&](int64_t x, int64_t y, int64_t z) { return inside[size_t(x + n[0] * (y + n[1] * z))]; };

  // Vertices keyed by their doubled coordinates in the padded box: below 8 x its voxels < 2^63.
  TriangleMesh mesh;
  std::unordered_map<uint64_t, int32_t> index;
  auto vertex = [&](int64_t x2, int64_t y2, int64_t z2) {
    const uint64_t key = uint64_t(x2 + 2 * n[0] * (y2 + 2 * n[1] * z2));
    const auto [it, fresh] = index.emplace(key, int32_t(mesh.vertices_mm.size()));
    if (fresh) {
      mesh.vertices_mm.push_back(g.index_to_physical(
          {double(lo[0]) + 0.5 * double(x2), double(lo[1]) + 0.5 * double(y2), double(lo[2]) + 0.5 * double(z2)}));
    }
    return it->second;
  };
  for (int64_t z = 0; z + 1 < n[2]; ++z) {
    for (int64_t y = 0; y + 1 < n[1]; ++y) {
      for (int64_t x = 0; x + 1 < n[0]; ++x) {
        int c = 0;
        for (int bit = 0; bit < 8; ++bit) c |= at(x + (bit & 1), y + ((bit >> 1) & 1), z + ((bit >> 2) & 1)) << bit;
        for (const CubeCaseTriangle& t : cases.triangles[size_t(c)]) {
          std::array<int32_t, 3> tri;
          for (size_t v = 0; v < 3; ++v) tri[v] = vertex(2 * x + t[v][0], 2 * y + t[v][1], 2 * z + t[v][2]);
          mesh.triangles.push_back(tri);
        }
      }
    }
  }
  // Outwards: the signed volume (sum of tetrahedra with the origin at a vertex) is positive.
  const Vec3 o = mesh.vertices_mm.front();
  double six_volume = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = mesh.vertices_mm[size_t(t[0])] - o, b2 = mesh.vertices_mm[size_t(t[1])] - o,
               c2 = mesh.vertices_mm[size_t(t[2])] - o;
    six_volume += dot(a, cross(b2, c2));
  }
  if (six_volume < 0)
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

}  // namespace soiq
