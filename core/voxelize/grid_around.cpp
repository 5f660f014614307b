#include "core/voxelize/grid_around.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace soiq {

Result<ImageGeometry> grid_around(const TriangleMesh& mesh, const Vec3& spacing_mm, int margin_voxels) {
  if (mesh.vertices_mm.empty()) return invalid_argument("cannot build a grid around an empty mesh");
  if (margin_voxels < 0) return invalid_argument("margin must be >= 0 voxels");
  for (double s : spacing_mm) {
    if (!(s > 0) || !std::isfinite(s)) return invalid_argument("spacing must be finite and > 0 mm");
  }
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi = -1.0 * lo;
  for (const Vec3& p : mesh.vertices_mm) {
    for (int a = 0; a < 3; ++a) {
      if (!std::isfinite(p[a])) return invalid_argument("mesh has NaN or infinite vertex coordinates");
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  return grid_around_box(lo, hi, spacing_mm, margin_voxels);
}

Result<ImageGeometry> grid_around_box(const Vec3& lo, const Vec3& hi, const Vec3& spacing_mm, int margin_voxels) {
  if (margin_voxels < 0) return invalid_argument("margin must be >= 0 voxels");
  for (int a = 0; a < 3; ++a) {
    const double s = spacing_mm[a];
    if (!(s > 0) || !std::isfinite(s)) return invalid_argument("spacing must be finite and > 0 mm");
    if (!std::isfinite(lo[a]) || !std::isfinite(hi[a]) || lo[a] > hi[a])
      return invalid_argument("bounding box must be finite with min <= max");
  }
  ImageGeometry g;
  g.spacing_mm = spacing_mm;
  for (int a = 0; a < 3; ++a) {
    const double first = std::floor(lo[a] / spacing_mm[a]) - margin_voxels;
    const double last = std::ceil(hi[a] / spacing_mm[a]) + margin_voxels;
    const double n = last - first + 1;
    if (n > 1e12)
      return invalid_argument("mesh extent is absurd for a spacing of " + std::to_string(spacing_mm[a]) + " mm");
    g.origin_mm[a] = first * spacing_mm[a];
    g.dims[a] = int64_t(n);
  }
  return g;
}

}  // namespace soiq
