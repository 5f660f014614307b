#include "bench/scanline_floor.h"

#include <algorithm>
#include <cmath>

#include "core/base/cpu_dispatch.h"
#include "core/base/physical_to_lattice.h"

namespace soiq::bench {

namespace {

int64_t lattice_points(const TriangleMesh& mesh, const ImageGeometry& g) {
  const PhysicalToLattice to_lattice(g);
  const double last_j = double(g.dims[1] - 1), last_k = double(g.dims[2] - 1);
  int64_t points = 0;
  double x_sum = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3 a = to_lattice(mesh.vertices_mm[size_t(t[0])]);
    const Vec3 b = to_lattice(mesh.vertices_mm[size_t(t[1])]);
    const Vec3 c = to_lattice(mesh.vertices_mm[size_t(t[2])]);
    const int64_t j_lo = int64_t(std::max(std::ceil(std::min({a[1], b[1], c[1]})), 0.0));
    const int64_t j_hi = int64_t(std::min(std::floor(std::max({a[1], b[1], c[1]})), last_j));
    const int64_t k_lo = int64_t(std::max(std::ceil(std::min({a[2], b[2], c[2]})), 0.0));
    const int64_t k_hi = int64_t(std::min(std::floor(std::max({a[2], b[2], c[2]})), last_k));
    points += std::max<int64_t>(j_hi - j_lo + 1, 0) * std::max<int64_t>(k_hi - k_lo + 1, 0);
    x_sum += a[0];  // x is part of the mapping every method needs: kept from being optimised away
  }
  return points + (x_sum > 1e300 ? 1 : 0);
}

}  // namespace

FloorRun scanline_floor(const TriangleMesh& mesh, const ImageGeometry& geometry) {
  FloorRun out;
  out.lattice_points = cpu_dispatch([&] { return lattice_points(mesh, geometry); });
  out.mask.geometry = geometry;
  out.mask.voxels.assign(size_t(geometry.voxel_count()), 0);
  return out;
}

}  // namespace soiq::bench
