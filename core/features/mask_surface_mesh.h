#pragma once
// The marching-cubes surface of a mask built as a mesh in mm, for the grids on which
// mask_surface_shape's closed forms do not hold: an unevenly spaced series, whose cubes change
// height from one pair of slices to the next.
//
// Inputs   volume  runs on a valid grid, not empty.
//          cases   the marching-cubes implementation's case table (marching_cubes_table() for
//                  soiq's marching_cubes).
// Output   every cube of 2 x 2 x 2 voxel centres around the mask (padded by one voxel of
//          outside, as marching_cubes pads) contributes its case's triangles, their vertices (edge
//          midpoints) shared between cubes and mapped by volume.geometry.index_to_physical, which
//          is affine within a cube's pair of slices: the triangles of marching_cubes(mask), the
//          whole surface wound outwards (flipped when its signed volume says inwards).
// Errors   INVALID_ARGUMENT an empty volume or a malformed one. RESOURCE_EXHAUSTED when the
//          mask's bounding box, padded, holds more than `max_voxels` voxels.
// Cost     O(voxels of the padded bounding box) time and a byte per such voxel, plus the mesh.

#include <cstdint>

#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/features/cube_case_table.h"

namespace soiq {

Result<TriangleMesh> mask_surface_mesh(const RunLengthVolume& volume, const CubeCaseTable& cases,
                                       int64_t max_voxels = kDefaultMaxVoxels);

}  // namespace soiq
