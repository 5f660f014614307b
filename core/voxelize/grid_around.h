#pragma once
// An axis-aligned grid (identity direction) around a surface model at a requested spacing, for
// conversions that have no reference image (docs/DESIGN.md, "Coordinates and grids").
//
// Inputs   mesh (LPS mm, finite vertices), spacing per axis (mm, > 0), margin in voxels (>= 0).
// Output   origin snapped to a multiple of the spacing (so the same mesh always lands on the same
//          lattice), covering the mesh's bounding box plus `margin` voxel centres on each side.
// Errors   INVALID_ARGUMENT for an empty mesh, a non-finite vertex, spacing <= 0, margin < 0.
// Cost     O(V).

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<ImageGeometry> grid_around(const TriangleMesh& mesh, const Vec3& spacing_mm, int margin_voxels);

// The same grid from the mesh's bounding box alone (lo, hi in mm), so a server can name the grid of
// a stored surface (for its feature cache) without decoding the surface. INVALID_ARGUMENT for a box
// that is not finite or has lo > hi, spacing <= 0, margin < 0.
Result<ImageGeometry> grid_around_box(const Vec3& lo, const Vec3& hi, const Vec3& spacing_mm, int margin_voxels);

}  // namespace soiq
