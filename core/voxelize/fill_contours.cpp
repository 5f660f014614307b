#include "core/voxelize/fill_contours.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

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

namespace fill_contours_detail {

// A contour in the grid's index space, placed on its slice.
struct PlacedContour {
  std::vector<Vec3> u;   // the points in continuous index space
  int64_t slice = 0;     // the nearest image plane
  double offset_mm = 0;  // signed distance of the contour's plane from it along the slice normal
};

std::string mm(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g mm", x);
  return buf;
}

std::string share(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace fill_contours_detail

Result<ContourFill> fill_contours(const std::vector<PlanarContour>& contours, const ImageGeometry& geometry,
                                  FillRule rule, double slice_tolerance_voxels, int64_t max_voxels,
                                  double planarity_tolerance_mm) {
  using fill_contours_detail::mm;
  using fill_contours_detail::PlacedContour;
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, max_voxels));
  ContourFill out;
  // Distances along the slice normal: on a sheared (tilted) grid the k axis is longer than that.
  const double sz = geometry.slice_distance_mm();
  const bool sheared = geometry.sheared(), uneven = geometry.uneven();
  const Mat3 frame = geometry.frame();
  const Vec3 normal{frame[0][2], frame[1][2], frame[2][2]};
  std::vector<PlacedContour> placed;
  for (size_t c = 0; c < contours.size(); ++c) {
    const auto& points = contours[c].points_mm;
    if (points.size() < 3) {
      return invalid_argument("contour " + std::to_string(c) + " has " + std::to_string(points.size()) +
                              " points; a closed planar contour needs at least 3");
    }
    PlacedContour pc;
    pc.u.resize(points.size());
    // Heights along k in the grid's lattice (the index itself unless the slices are unevenly
    // spaced), where distances along the normal are linear: sz mm per unit.
    std::vector<double> zs(points.size());
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec3& p = points[i];
      if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
        return invalid_argument("contour " + std::to_string(c) + " has NaN or infinite coordinates");
      }
      pc.u[i] = geometry.physical_to_index(p);
      zs[i] = uneven ? geometry.physical_to_lattice(p)[2] : pc.u[i][2];
    }
    // The contour's plane: the median of its points along the slice normal, so that a point that
    // strays is measured from where the others lie. Every point must lie on it (a contour is
    // planar); the whole contour then goes to the nearest image plane.
    std::vector<double> sorted = zs;
    std::nth_element(sorted.begin(), sorted.begin() + ptrdiff_t(sorted.size() / 2), sorted.end());
    const double z_mean = sorted[sorted.size() / 2];
    double worst = 0;
    for (const double z : zs) worst = std::max(worst, std::abs(z - z_mean) * sz);
    if (worst > planarity_tolerance_mm) {
      return invalid_argument("contour " + std::to_string(c) + " is not planar: a point lies " + mm(worst) +
                              " from the contour's plane along the slice normal (tolerance " +
                              mm(planarity_tolerance_mm) + ")");
    }
    // The nearest plane, and how far off it the contour is as a share of the step to the next
    // plane on its side (the spacing, unless uneven).
    const double k_round = std::round(uneven ? geometry.slice_index(z_mean) : z_mean);
    const double z_plane = geometry.lattice_z(k_round);
    const double side = z_mean >= z_plane ? 1 : -1;
    const double step = uneven ? std::abs(geometry.lattice_z(k_round + side) - z_plane) : 1.0;
    pc.offset_mm = (z_mean - z_plane) * sz;
    if (std::abs(z_mean - z_plane) > slice_tolerance_voxels * step) {
      return invalid_argument("contour " + std::to_string(c) + " lies " + mm(std::abs(pc.offset_mm)) +
                              " from the nearest image plane (slice " + std::to_string(int64_t(k_round)) +
                              "), more than " + mm(slice_tolerance_voxels * step * sz) + " (" +
                              fill_contours_detail::share(slice_tolerance_voxels) +
                              " of the slice spacing): is it the right reference series?");
    }
    if (sheared) {
      // A point goes to its plane along the normal, not along the leaning k axis: on its plane the
      // two agree, off it they part by the tilt.
      for (size_t i = 0; i < points.size(); ++i)
        pc.u[i] = geometry.physical_to_index(points[i] - ((zs[i] - z_plane) * sz) * normal);
    }
    if (k_round < 0 || k_round >= double(geometry.dims[2])) {
      ++out.contours_outside_grid;
      continue;
    }
    pc.slice = int64_t(k_round);
    placed.push_back(std::move(pc));
  }
  // Contours drawn on a finer series than the referenced one reach one image plane from several
  // planes of their own: XOR-ing near copies of one outline would cut the structure to slivers, so
  // a slice keeps the contours of the plane nearest to it (planes apart by more than the planarity
  // tolerance are different planes).
  std::vector<double> nearest(size_t(geometry.dims[2]), HUGE_VAL);
  for (const PlacedContour& pc : placed)
    nearest[size_t(pc.slice)] = std::min(nearest[size_t(pc.slice)], std::abs(pc.offset_mm));
  std::vector<LineCrossingAt> crossings;
  for (const PlacedContour& pc : placed) {
    if (std::abs(pc.offset_mm) > nearest[size_t(pc.slice)] + planarity_tolerance_mm) {
      ++out.contours_superseded;
      continue;
    }
    for (size_t i = 0; i < pc.u.size(); ++i)
      edge_crossings(pc.u[i], pc.u[(i + 1) % pc.u.size()], pc.slice, geometry.dims[0], geometry.dims[1], crossings);
  }
  LineRuns lines = fill_lines(crossings, geometry.dims[1] * geometry.dims[2], geometry.dims[0], rule, false);
  out.volume.geometry = geometry;
  out.volume.line_start = std::move(lines.line_start);
  out.volume.runs = std::move(lines.runs);
  return out;
}

}  // namespace soiq
