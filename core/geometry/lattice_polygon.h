#pragma once
// Convex hull and diameter of integer points in a plane, exact: the 2D step of the mask-surface
// features computed from runs (mask_surface_shape.h, mask_maximum_2d_diameters.h), whose points
// are marching-cubes vertices in doubled index coordinates (every coordinate an integer).
//
// lattice_hull
//   Input   points sorted by (u, v) ascending, distinct; |coordinates| < 2^30.
//   Output  the hull's vertices counter-clockwise, starting at the first point; points on an
//           edge's interior (collinear) are left out. One point gives itself; all collinear
//           points give the two ends. Turns are exact integer cross products (Andrew's monotone
//           chain, through lattice_hull_of_rows on each row's two ends).
//   Cost    O(n) time and memory. Thread-safe.
//
// lattice_hull_of_rows
//   Input   rows ascending in u, each holding its least and greatest v (lo <= hi): the point set
//           {(u, lo), (u, hi)} of every row, as the mask sweep and the hull shortlist keep it.
//   Output  the hull of those points, as lattice_hull describes it.
//   Method  Andrew's chains with each point offered to the one chain it can be on: a row's lo
//           only to the lower chain, its hi only to the upper one (a hi above its lo is never a
//           lower-chain vertex but at the last row, nor a lo an upper one but at the first).
//   Cost    O(rows), half the turns of offering every point to both chains. Thread-safe.
//
// lattice_polygon_diameter
//   Input   a convex polygon as lattice_hull returns it; scale_u, scale_v > 0: mm per unit along
//           u and v (a grid's anisotropic spacing, halved for doubled coordinates).
//   Output  max over vertex pairs of sqrt((du scale_u)^2 + (dv scale_v)^2); 0 for fewer than 2.
//   Method  rotating calipers over the antipodal pairs, found with exact integer areas. An affine
//           map (the scaling) keeps parallel supporting lines parallel, so the antipodal pairs of
//           the scaled polygon are those of the integer one, and its diameter is one of them.
//   Cost    O(h) for h vertices. Thread-safe.
//   The overload with step_u, step_v measures du step_u + dv step_v instead: any linear map of
//   the plane (a sheared grid's planes that hold its leaning k axis), by the same argument.

#include <cstdint>
#include <vector>

#include "core/base/vec3.h"

namespace soiq {

struct LatticePoint {
  int64_t u = 0, v = 0;
  bool operator==(const LatticePoint&) const = default;
};

std::vector<LatticePoint> lattice_hull(const std::vector<LatticePoint>& sorted_points);

struct LatticeRow {
  int64_t u = 0, lo = 0, hi = 0;
};

std::vector<LatticePoint> lattice_hull_of_rows(const std::vector<LatticeRow>& rows);

double lattice_polygon_diameter(const std::vector<LatticePoint>& hull, double scale_u, double scale_v);
double lattice_polygon_diameter(const std::vector<LatticePoint>& hull, const Vec3& step_u, const Vec3& step_v);

}  // namespace soiq
