#include "core/features/maximum_2d_diameters.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace soiq {
namespace {

struct PlanePoint {
  int64_t plane = 0;  // round(2 * index coordinate along the axis)
  double u = 0, v = 0;
  bool operator<(const PlanePoint& o) const {
    if (plane != o.plane) return plane < o.plane;
    if (u != o.u) return u < o.u;
    return v < o.v;
  }
};

// z of (b - a) x (c - a): > 0 for a counter-clockwise turn.
double turn(const PlanePoint& a, const PlanePoint& b, const PlanePoint& c) {
  return (b.u - a.u) * (c.v - a.v) - (b.v - a.v) * (c.u - a.u);
}

// Diameter of points [first, last), sorted by (u, v): Andrew's monotone chain hull, then all
// pairs of hull vertices (hulls of one plane of a mesh have few vertices).
double plane_diameter(const PlanePoint* first, const PlanePoint* last, std::vector<PlanePoint>& hull) {
  const size_t n = size_t(last - first);
  if (n < 2) return 0;
  hull.assign(2 * n, PlanePoint{});
  size_t h = 0;
  for (size_t p = 0; p < n; ++p) {  // lower chain
    while (h >= 2 && turn(hull[h - 2], hull[h - 1], first[p]) <= 0) --h;
    hull[h++] = first[p];
  }
  for (size_t p = n - 1, lower = h + 1; p-- > 0;) {  // upper chain
    while (h >= lower && turn(hull[h - 2], hull[h - 1], first[p]) <= 0) --h;
    hull[h++] = first[p];
  }
  // Collinear points collapse to the two extremes, which is all the diameter needs.
  double best = 0;
  for (size_t a = 0; a < h; ++a) {
    for (size_t b = a + 1; b < h; ++b) {
      const double du = hull[a].u - hull[b].u, dv = hull[a].v - hull[b].v;
      best = std::max(best, du * du + dv * dv);
    }
  }
  return std::sqrt(best);
}

// Max over planes of constant index coordinate `axis`; `vertices_mm` the points in LPS.
double diameter_along(const std::vector<Vec3>& index_coords, const std::vector<Vec3>& vertices_mm,
                      const ImageGeometry& grid, int axis) {
  const Vec3& spacing = grid.spacing_mm;
  const int ua = (axis + 1) % 3, va = (axis + 2) % 3;
  // On a sheared grid the planes that hold the leaning k axis are not spanned at right angles, and
  // on an unevenly spaced one the k index is not proportional to distance: in-plane coordinates
  // come from the points in mm, on an orthonormal basis (e1, e2) of the plane.
  const bool in_mm = (grid.sheared() || grid.uneven()) && axis != 2;
  const Mat3& d = grid.direction;
  const Vec3 a_u = spacing[ua] * Vec3{d[0][ua], d[1][ua], d[2][ua]};
  const Vec3 a_v = spacing[va] * Vec3{d[0][va], d[1][va], d[2][va]};
  const Vec3 e1 = (1 / norm(a_u)) * a_u;
  const Vec3 v_rest = a_v - dot(a_v, e1) * e1;
  const Vec3 e2 = (1 / norm(v_rest)) * v_rest;
  std::vector<PlanePoint> points(index_coords.size());
  for (size_t p = 0; p < index_coords.size(); ++p) {
    const Vec3& c = index_coords[p];
    if (in_mm) {
      points[p] = {std::llround(2 * c[axis]), dot(vertices_mm[p], e1), dot(vertices_mm[p], e2)};
      continue;
    }
    // With an orthonormal direction matrix, in-plane distances in mm are index differences times
    // the spacing, so the plane needs no 3D coordinates.
    points[p] = {std::llround(2 * c[axis]), c[ua] * spacing[ua], c[va] * spacing[va]};
  }
  std::sort(points.begin(), points.end());
  std::vector<PlanePoint> hull;
  double best = 0;
  for (size_t begin = 0; begin < points.size();) {
    size_t end = begin;
    while (end < points.size() && points[end].plane == points[begin].plane) ++end;
    best = std::max(best, plane_diameter(points.data() + begin, points.data() + end, hull));
    begin = end;
  }
  return best;
}

}  // namespace

Result<Maximum2DDiameters> maximum_2d_diameters(const TriangleMesh& mesh, const ImageGeometry& grid) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(grid));
  if (mesh.vertices_mm.empty()) return invalid_argument("maximum 2D diameters of an empty mesh are undefined");
  std::vector<Vec3> index_coords(mesh.vertices_mm.size());
  for (size_t p = 0; p < mesh.vertices_mm.size(); ++p) {
    const Vec3& v = mesh.vertices_mm[p];
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
      return invalid_argument("mesh vertex " + std::to_string(p) + " has a non-finite coordinate");
    }
    index_coords[p] = grid.physical_to_index(v);
  }
  Maximum2DDiameters out;
  out.row_mm = diameter_along(index_coords, mesh.vertices_mm, grid, 0);
  out.column_mm = diameter_along(index_coords, mesh.vertices_mm, grid, 1);
  out.slice_mm = diameter_along(index_coords, mesh.vertices_mm, grid, 2);
  return out;
}

}  // namespace soiq
