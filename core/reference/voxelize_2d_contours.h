#pragma once
// The paper's 2D method, a benchmark peer and second oracle: cut the mesh with each slice plane
// z = k (continuous index space) into oriented 2D contour segments, then for every voxel centre
// (i, j) of the slice cast a ray along +x against the segments of its row and sum the signed
// crossings strictly ahead (x > i). Shares no code with voxelize_1d.
//
// Inputs   as voxelize_3d_raycast: a closed, consistently oriented mesh in LPS mm, a grid, a rule.
// Output   Voxel (i,j,k) is inside iff the signed crossings ahead of it sum to nonzero (kNonZero)
//          or are odd in number (kEvenOdd); a segment counts +1 when it runs towards +y (the
//          triangle's n_x > 0, a leaving crossing), -1 towards -y.
//          Ties use the symbolic perturbation of voxelize_1d, the point (j + e, k + e^2):
//          a vertex with u_z == k is below the plane (z = k + e^2), and a segment endpoint with
//          y == j is below the row (y = j + e). Edge/plane and segment/row intersections are
//          computed from the lower endpoint, so the segments of neighbouring triangles meet
//          exactly and every row crosses a closed contour an even number of times.
//          Equal to voxelize_3d_raycast and voxelize_1d on meshes whose surface does not pass
//          through voxel centres (e.g. marching-cubes surfaces); on exact ties in x the crossing
//          x, computed by two interpolations instead of one, may round to the other side.
// Errors   as voxelize_3d_raycast.
// Cost     O(T + segments) per slice for the cut (triangles bucketed by slice) plus
//          O(voxels x segments per row) for the rays. Single-threaded; thread-safe.

#include "core/base/fill_rule.h"
#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<RunLengthVolume> voxelize_2d_contours(const TriangleMesh& mesh, const ImageGeometry& geometry,
                                             FillRule rule = FillRule::kNonZero);

}  // namespace soiq
