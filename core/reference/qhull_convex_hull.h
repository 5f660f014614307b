#pragma once
// An independent oracle for convex_hull.h, for tests and benchmarks only: the same hull computed
// by Qhull's reentrant library ("qhull Qt": facet merging in floating point, triangulated output).
//
// Inputs   points in any frame, finite; at least 4 and not all coplanar.
// Output   ConvexHull (convex_hull.h), except that vertex_indices are Qhull's vertices: points
//          within Qhull's round-off (~1e-13 relative) of a facet may be left out or kept, so values
//          agree with convex_hull's to about that much.
// Errors   INVALID_ARGUMENT  fewer than 4 points, a non-finite coordinate, too many points, or a
//                            degenerate set; the message carries Qhull's first error line ("QH...").
//          INTERNAL          any other Qhull failure. Qhull never prints and never exits.
// Cost     O(n log n) expected. Thread-safe (one Qhull context per call).

#include "core/geometry/convex_hull.h"

namespace soiq {

Result<ConvexHull> qhull_convex_hull(const std::vector<Vec3>& points_mm);

}  // namespace soiq
