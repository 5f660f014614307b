#include "core/features/surface_shape.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "core/geometry/convex_hull.h"
#include "core/geometry/hull_vertex_candidates.h"
#include "core/geometry/point_set_diameter.h"
#include "core/geometry/surface_area_volume.h"

namespace soiq {

ConvexHull skipped_hull() {
  ConvexHull hull;
  hull.volume_mm3 = std::numeric_limits<double>::quiet_NaN();
  hull.area_mm2 = std::numeric_limits<double>::quiet_NaN();
  return hull;
}

Result<SurfaceShape> surface_shape(const TriangleMesh& mesh, const Mat3& box_axes, HullPart hull_part) {
  for (const auto& row : box_axes) {
    for (const double x : row) {
      if (!std::isfinite(x)) return invalid_argument("bounding-box axes are not finite");
    }
  }
  SOIQ_ASSIGN_OR_RETURN(const SurfaceAreaVolume measures, surface_area_volume(mesh));
  const size_t nv = mesh.vertices_mm.size();
  // The used vertices, and their extents along the box axes (the columns of box_axes).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};
  // The hull and the diameter work on a copy of the used vertices; without them none is made (a
  // fresh copy of a large surface's vertices was a tenth of a cold query, most of it page faults).
  const bool keep_points = hull_part != HullPart::kSkip;
  std::vector<Vec3> points;
  if (keep_points) points.reserve(nv);
  for (size_t v = 0; v < nv; ++v) {
    if (!measures.used[v]) continue;
    const Vec3& p = mesh.vertices_mm[v];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      return invalid_argument("mesh vertex " + std::to_string(v) + " has a non-finite coordinate");
    }
    if (keep_points) points.push_back(p);
    for (int c = 0; c < 3; ++c) {
      const double x = box_axes[0][c] * p[0] + box_axes[1][c] * p[1] + box_axes[2][c] * p[2];
      lo[c] = std::min(lo[c], x), hi[c] = std::max(hi[c], x);
    }
  }

  if (hull_part == HullPart::kSkip) {
    return surface_shape_from_measures(measures.volume_mm3, measures.area_mm2, skipped_hull(),
                                       std::numeric_limits<double>::quiet_NaN(), hi - lo);
  }
  // The hull of the shortlist only: it is the vertices' hull (hull_vertex_candidates.h).
  std::vector<Vec3> candidates;
  for (const int64_t v : hull_vertex_candidates(points)) candidates.push_back(points[size_t(v)]);
  if (hull_part == HullPart::kDiameterOnly) {
    return surface_shape_from_measures(measures.volume_mm3, measures.area_mm2, skipped_hull(),
                                       point_set_diameter(candidates), hi - lo);
  }
  if (candidates.size() < 4) candidates = points;  // a degenerate set: convex_hull names the problem
  SOIQ_ASSIGN_OR_RETURN(const ConvexHull hull, convex_hull(candidates));
  // The farthest pair of a set is a pair of its hull's vertices.
  std::vector<Vec3> hull_points;
  hull_points.reserve(hull.vertex_indices.size());
  for (const int64_t v : hull.vertex_indices) hull_points.push_back(candidates[size_t(v)]);
  const double diameter = point_set_diameter(hull_points);
  return surface_shape_from_measures(measures.volume_mm3, measures.area_mm2, hull, diameter, hi - lo);
}

SurfaceShape surface_shape_from_measures(double volume, double area, const ConvexHull& hull, double diameter_mm,
                                         const Vec3& e) {
  SurfaceShape out;
  out.mesh_volume_mm3 = volume;
  out.surface_area_mm2 = area;
  out.surface_volume_ratio = area / volume;
  constexpr double kPi = std::numbers::pi;
  const double sphere_area = std::cbrt(36 * kPi * volume * volume);  // area of the sphere of volume V
  out.compactness_1 = volume / (std::sqrt(kPi) * std::pow(area, 1.5));
  out.compactness_2 = 36 * kPi * volume * volume / (area * area * area);
  out.spherical_disproportion = area / sphere_area;
  out.sphericity = sphere_area / area;
  out.asphericity = area / sphere_area - 1;  // (A^3 / (36 pi V^2))^(1/3) - 1
  out.maximum_3d_diameter_mm = diameter_mm;
  out.convex_hull_volume_mm3 = hull.volume_mm3;
  out.convex_hull_area_mm2 = hull.area_mm2;
  out.volume_density_convex_hull = volume / hull.volume_mm3;
  out.area_density_convex_hull = area / hull.area_mm2;
  out.volume_density_aabb = volume / (e[0] * e[1] * e[2]);
  out.area_density_aabb = area / (2 * (e[0] * e[1] + e[1] * e[2] + e[0] * e[2]));
  return out;
}

}  // namespace soiq
