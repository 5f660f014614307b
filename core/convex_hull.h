#pragma once
// The convex hull of a 3D point set, for the maximum 3D diameter and the convex-hull densities of
// a structure (DESIGN.md "Features"; IBSI L0JK, R3ER, 7T7F). Built by Qhull's reentrant library
// (Barber, Dobkin & Huhdanpaa, "The Quickhull algorithm for convex hulls", ACM TOMS 22(4), 1996)
// with facet merging and triangulated output ("qhull Qt").
//
// Inputs   points in LPS mm (any frame), finite; at least 4 and not all coplanar.
// Output   vertex_indices  indices into `points` of the hull's vertices, ascending. Points within
//                          Qhull's round-off (~1e-13 relative) of a facet may be left out, so
//                          lengths computed from the vertices err by at most that much.
//          triangles       the hull's boundary as index triples into `points`, facing outward.
//          volume_mm3, area_mm2  of the hull, summed over those triangles.
// Errors   INVALID_ARGUMENT  fewer than 4 points, a non-finite coordinate, more than 2^31-1
//                            points, or a degenerate set (all coplanar/collinear: Qhull QH6154
//                            and friends); the message carries Qhull's first error line.
//          INTERNAL          any other Qhull failure, with its message.
//          Qhull never prints (its messages go to a memory stream) and never exits the process.
// Cost     O(n log n) expected time, O(n) memory. Thread-safe (one Qhull context per call).

#include <array>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "core/vec3.h"

namespace soiq {

struct ConvexHull {
  std::vector<int64_t> vertex_indices;
  std::vector<std::array<int64_t, 3>> triangles;
  double volume_mm3 = 0;
  double area_mm2 = 0;
};

Result<ConvexHull> convex_hull(const std::vector<Vec3>& points_mm);

}  // namespace soiq
