#pragma once
// The convex hull of a 3D point set, for the maximum 3D diameter and the convex-hull densities of
// a structure (docs/DESIGN.md "Features"; IBSI L0JK, R3ER, 7T7F). Quickhull (Barber, Dobkin &
// Huhdanpaa, "The Quickhull algorithm for convex hulls", ACM TOMS 22(4), 1996) decided by exact
// orientation signs (exact_predicates.h), so lattice inputs with many coplanar points, the usual
// case for marching-cubes and contour surfaces, need no merging and no tolerance.
//
// Inputs   points in LPS mm (any frame), finite; at least 4 and not all coplanar.
// Output   vertex_indices  indices into `points` of the hull's extreme points (its corners),
//                          ascending, one index per distinct position: a point on a hull edge or
//                          inside a hull facet is not listed. Exact.
//          triangles       the hull's boundary as index triples into `points`, facing outward. A
//                          planar facet comes triangulated, possibly using points inside it.
//          volume_mm3, area_mm2  of the hull, summed over those triangles (double rounding only).
// Errors   INVALID_ARGUMENT  fewer than 4 points, a non-finite coordinate, more than 2^31-1
//                            points, or a degenerate set (all points coplanar or collinear).
// Cost     O(n log n) expected for points in general position, O(n h) worst case (h hull
//          vertices); O(n) memory (dead faces are reused, so faces follow the hull's size).
//          Measured (one core, Release): the 2,414-point shortlist of SM1's marching-cubes
//          surface 0.58 ms; the 95,202 vertices of a smoothed real tumour surface
//          (bench/smoothed_structure.h, 21,615 corners) about 30 ms, where qhull takes 0.10 s; the
//          79,602 vertices of uv_sphere(50, 200, 400), every one a corner, 0.09 s. There the time
//          is the Quickhull's own steps (33,000 points added, 740,000 points handed from dead faces
//          to new ones, 6.1 million height tests), each a few random reads; the output, summation
//          order included, is pinned to the last bit (convex_hull_bits_test.cpp). Thread-safe,
//          no global state.

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/status.h"
#include "core/base/vec3.h"

namespace soiq {

struct ConvexHull {
  std::vector<int64_t> vertex_indices;
  std::vector<std::array<int64_t, 3>> triangles;
  double volume_mm3 = 0;
  double area_mm2 = 0;
};

Result<ConvexHull> convex_hull(const std::vector<Vec3>& points_mm);

}  // namespace soiq
