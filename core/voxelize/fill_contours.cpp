#include "core/voxelize/fill_contours.h"

#include <cmath>
#include <cstdio>

#include "core/geometry/exact_predicates.h"
#include "core/voxelize/line_fill.h"

namespace soiq {

namespace {

// Appends the crossings of edge p -> q (index space, same slice k) with the row lines y = j + e.
// An endpoint with y == j counts as below the line, so of two edges meeting at a vertex on the
// line exactly one crosses it when the contour passes through, and neither or both when it only
// touches: the parity stays right without an epsilon.
void edge_crossings(const Vec3& p, const Vec3& q, int64_t k, int64_t nx, int64_t ny, std::vector<LineCrossingAt>& out) {
  if (p[1] == q[1]) return;  // parallel to the rows: never crosses a perturbed line
  const bool up = q[1] > p[1];
  const Vec3& lo = up ? p : q;
  const Vec3& hi = up ? q : p;
  // Lines j with lo.y <= j < hi.y are crossed.
  const int64_t j_first = std::max<int64_t>(0, int64_t(std::ceil(lo[1])));
  const int64_t j_last = std::min<int64_t>(ny - 1, int64_t(std::ceil(hi[1])) - 1);
  const double slope = (hi[0] - lo[0]) / (hi[1] - lo[1]);
  constexpr double kEps = 1.1102230246251565e-16;
  for (int64_t j = j_first; j <= j_last; ++j) {
    // From the lower endpoint, whatever the edge's direction: both contours sharing an edge (a
    // keyhole) get the same x.
    const double t = (double(j) - lo[1]) * slope;
    const double x = lo[0] + t;
    // Near a voxel centre, decide the side exactly: the crossing is at or before centre m iff
    // (m, j) is on or right of the upward edge lo -> hi.
    int64_t centre = clamped_ceil(x, nx);
    const double m = std::nearbyint(x);
    if (std::abs(x - m) <= 8 * kEps * (std::abs(lo[0]) + std::abs(t) + 1)) {
      centre = clamped_ceil(orient2d_sign(lo[0], lo[1], hi[0], hi[1], m, double(j)) <= 0 ? m : m + 1, nx);
    }
    // Counter-clockwise contours (seen from +k) have their interior on the left: an edge going
    // down (-y) is met first along +x, so it is the entering one.
    out.push_back({j + ny * k, {centre, up ? -1 : +1}});
  }
}

}  // namespace

Result<ContourFill> fill_contours(const std::vector<PlanarContour>& contours, const ImageGeometry& geometry,
                                  FillRule rule, double slice_tolerance_voxels, int64_t max_voxels) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, max_voxels));
  ContourFill out;
  std::vector<LineCrossingAt> crossings;
  std::vector<Vec3> u;
  for (size_t c = 0; c < contours.size(); ++c) {
    const auto& points = contours[c].points_mm;
    if (points.size() < 3) {
      return invalid_argument("contour " + std::to_string(c) + " has " + std::to_string(points.size()) +
                              " points; a closed planar contour needs at least 3");
    }
    u.resize(points.size());
    double k_sum = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec3& p = points[i];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
        return invalid_argument("contour " + std::to_string(c) + " has NaN or infinite coordinates");
      }
      u[i] = geometry.physical_to_index(p);
      k_sum += u[i][2];
    }
    const double k_mean = k_sum / double(points.size());
    const double k_round = std::round(k_mean);
    for (const Vec3& v : u) {
      if (std::abs(v[2] - k_round) > slice_tolerance_voxels) {
        char buf[200];
        std::snprintf(buf, sizeof buf,
                      "contour %zu does not lie in a slice plane of the grid: a point is %.3f voxels from slice "
                      "%.0f (tolerance %.3f); is it the right reference series?",
                      c, v[2] - k_round, k_round, slice_tolerance_voxels);
        return invalid_argument(buf);
      }
    }
    if (k_round < 0 || k_round >= double(geometry.dims[2])) {
      ++out.contours_outside_grid;
      continue;
    }
    const int64_t k = int64_t(k_round);
    for (size_t i = 0; i < u.size(); ++i)
      edge_crossings(u[i], u[(i + 1) % u.size()], k, geometry.dims[0], geometry.dims[1], crossings);
  }
  LineRuns lines = fill_lines(crossings, geometry.dims[1] * geometry.dims[2], geometry.dims[0], rule, false);
  out.volume.geometry = geometry;
  out.volume.line_start = std::move(lines.line_start);
  out.volume.runs = std::move(lines.runs);
  return out;
}

}  // namespace soiq
