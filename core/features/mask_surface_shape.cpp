#include "core/features/mask_surface_shape.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/geometry/point_set_diameter.h"

namespace soiq {
namespace {

__extension__ typedef __int128 Int128;  // exact sums of integer determinants

// Six times the index-space volume, times 8 (doubled coordinates): sum over the triangles of
// det(2 o + a, 2 o + b, 2 o + c) = det(a, b, c) + 2 o . ((b - a) x (c - a)), o the cube's corner.
Int128 volume_times_48(const MaskSurfaceSweep& sweep, const CubeCaseTable& cases) {
  Int128 sum = 0;
  for (size_t c = 0; c < 256; ++c) {
    if (sweep.cube_count[c] == 0) continue;
    int64_t det = 0, n[3] = {0, 0, 0};
    for (const CubeCaseTriangle& t : cases.triangles[c]) {
      const int64_t a[3] = {t[0][0], t[0][1], t[0][2]}, b[3] = {t[1][0], t[1][1], t[1][2]},
                    d[3] = {t[2][0], t[2][1], t[2][2]};
      det +=
          a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) + a[2] * (b[0] * d[1] - b[1] * d[0]);
      const int64_t e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, f[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      n[0] += e[1] * f[2] - e[2] * f[1];
      n[1] += e[2] * f[0] - e[0] * f[2];
      n[2] += e[0] * f[1] - e[1] * f[0];
    }
    sum += Int128(sweep.cube_count[c]) * det;
    for (size_t a = 0; a < 3; ++a) sum += 2 * Int128(sweep.corner_sum[c][a]) * n[a];
  }
  return sum;
}

// Surface area in mm2: per case, its triangles' area with the doubled coordinates mapped into mm
// by `half_step` (spacing / 2 along each grid axis; on a sheared grid the axes themselves, as the
// cube's edges are not at right angles), times the number of cubes of that case.
double area_mm2(const MaskSurfaceSweep& sweep, const CubeCaseTable& cases, const ImageGeometry& grid) {
  const Vec3 h = 0.5 * grid.spacing_mm;
  const bool sheared = grid.sheared();
  Mat3 half_step = grid.direction;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) half_step[r][c] *= h[size_t(c)];
  double area = 0;
  for (size_t c = 0; c < 256; ++c) {
    if (sweep.cube_count[c] == 0) continue;
    double case_area = 0;
    for (const CubeCaseTriangle& t : cases.triangles[c]) {
      Vec3 p[3];
      for (size_t v = 0; v < 3; ++v) {
        p[v] = {t[v][0] * h[0], t[v][1] * h[1], t[v][2] * h[2]};
        if (sheared) p[v] = mul(half_step, {double(t[v][0]), double(t[v][1]), double(t[v][2])});
      }
      case_area += norm(cross(p[1] - p[0], p[2] - p[0])) / 2;
    }
    area += double(sweep.cube_count[c]) * case_area;
  }
  return area;
}

// The extents of `points` along the columns of `frame`.
Vec3 frame_extent(const std::vector<Vec3>& points, const Mat3& frame) {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Vec3& p : points) {
    for (int c = 0; c < 3; ++c) {
      const double x = frame[0][c] * p[0] + frame[1][c] * p[1] + frame[2][c] * p[2];
      lo[size_t(c)] = std::min(lo[size_t(c)], x), hi[size_t(c)] = std::max(hi[size_t(c)], x);
    }
  }
  return hi - lo;
}

}  // namespace

Result<SurfaceShape> mask_surface_shape(const MaskSurfaceSweep& sweep, const ImageGeometry& grid,
                                        const CubeCaseTable& cases, HullPart hull_part) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(grid));
  if (sweep.empty) return invalid_argument("surface shape of an empty mask is undefined");
  const Vec3& s = grid.spacing_mm;
  // The mm3 volume is the index volume times the voxel volume (a linear map scales every volume
  // by its determinant). The sign follows the case table's winding, consistent over the surface
  // (marching_cubes flips it globally the same way).
  const double volume = std::fabs(double(volume_times_48(sweep, cases))) / 48 * grid.voxel_volume_mm3();
  const double area = area_mm2(sweep, cases, grid);
  if (!(volume > 0)) return internal_error("mask surface encloses no volume: the case table is broken");

  Vec3 extent{double(sweep.hi[0] - sweep.lo[0] + 1) * s[0], double(sweep.hi[1] - sweep.lo[1] + 1) * s[1],
              double(sweep.hi[2] - sweep.lo[2] + 1) * s[2]};
  const bool sheared = grid.sheared();
  if (hull_part == HullPart::kSkip && !sheared) {
    return surface_shape_from_measures(volume, area, skipped_hull(), std::numeric_limits<double>::quiet_NaN(), extent);
  }

  // The shortlist: vertices of all three of their planes' hulls.
  const PlaneFamily& fx = sweep.families[0];
  const PlaneFamily& fy = sweep.families[1];
  const PlaneFamily& fz = sweep.families[2];
  std::vector<Vec3> candidates;
  for (int64_t p = 0; p < fz.planes; ++p) {
    const int64_t z = p + fz.plane_base;
    for (const LatticePoint& q : fz.hulls[size_t(p)]) {
      const int64_t y = q.u, x = q.v;
      if (!fx.is_hull_vertex(x, z, y) || !fy.is_hull_vertex(y, z, x)) continue;
      candidates.push_back(grid.index_to_physical({0.5 * double(x), 0.5 * double(y), 0.5 * double(z)}));
    }
  }
  // On a sheared grid the box is along the slices' orthonormal frame, as surface_shape measures it:
  // its extremes are hull vertices, all among the candidates.
  if (sheared) extent = frame_extent(candidates, grid.frame());
  if (hull_part == HullPart::kSkip) {
    return surface_shape_from_measures(volume, area, skipped_hull(), std::numeric_limits<double>::quiet_NaN(), extent);
  }
  if (hull_part == HullPart::kDiameterOnly) {
    return surface_shape_from_measures(volume, area, skipped_hull(), point_set_diameter(candidates), extent);
  }
  SOIQ_ASSIGN_OR_RETURN(const ConvexHull hull, convex_hull(candidates));
  std::vector<Vec3> hull_points;
  hull_points.reserve(hull.vertex_indices.size());
  for (const int64_t v : hull.vertex_indices) hull_points.push_back(candidates[size_t(v)]);
  return surface_shape_from_measures(volume, area, hull, point_set_diameter(hull_points), extent);
}

}  // namespace soiq
