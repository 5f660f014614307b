#pragma once
// A shortlist of the points that can be vertices of a point set's convex hull, for a faster hull
// (convex_hull.h) of the same set: the hull of the shortlist IS the hull of the set.
//
// Fact used: a vertex of the 3D hull (an extreme point) is an extreme point of every subset that
// contains it, in particular of the points that share its exact x, its exact y or its exact z
// coordinate. So a point is dropped when, in one of its three axis planes, it is not a strict
// vertex of that plane's 2D hull: it is then a convex combination of other distinct points, hence
// not extreme; and since a finite set's hull is the hull of its extreme points, dropping any number
// of such points at once keeps the hull. Exact duplicates keep their first (lowest) index.
// Marching-cubes and contour surfaces put their vertices on shared planes (the half-voxel lattice,
// the slice planes), where this drops most points (a 64k-vertex lattice sphere keeps ~2.3k); for
// points in general position every plane holds one point and nothing is dropped (a sample of
// the x coordinates detects that case, and then every point is returned without sorting).
//
// Inputs   points in any frame, finite (not checked: the hull checks).
// Output   indices into `points`, ascending: every extreme point of conv(points) (one index per
//          distinct position) and possibly some others. 2D turns are exact (orient2d_sign).
// Errors   none.
// Cost     O(n) time and memory: three radix sorts (by x, y, z planes), each over the previous
//          family's survivors, then one monotone chain per plane over its rows' two ends. On a
//          small dyadic lattice (dyadic_lattice.h) whose bounding box's faces hold at most 8n + 2^16
//          lattice cells, dense per-row tables replace the sorts. Thread-safe.

#include <cstdint>
#include <vector>

#include "core/base/vec3.h"

namespace soiq {

std::vector<int64_t> hull_vertex_candidates(const std::vector<Vec3>& points);

}  // namespace soiq
