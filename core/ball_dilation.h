#pragma once
// Dilation of a structure by a ball of radius r mm on its own grid, straight on the runs (the
// shell region of regions.h without a dense box or a distance transform): a voxel is in the result
// iff its centre is within r mm of an inside voxel centre, each axis with its own spacing.
//
// Inputs   structure  runs on a valid grid (checked by the caller, regions.h);
//          radius_mm  finite, > 0.
// Output   runs on the same grid, clipped to it. "Within" is decided exactly as regions.h's
//          distance transform decides it: for offsets (di, dj, dk) voxels, with d_a = offset_a x
//          spacing_a, the double value (dk)^2 + ((dj)^2 + (di)^2), each square and sum rounded, is
//          <= r^2 (1 + 1e-12). That value grows with |di|, so each (dj, dk) has a largest |di|.
// Cost     O(lines of the grown box x (offsets (dj, dk) in the ball x runs per line + the line's
//          reach)): each line's pieces are united by a difference array, no sort. Cheaper than the
//          distance transform's O(box voxels) while the ball's cross section is small next to the
//          box (regions.h chooses). Thread-safe.

#include <cstdint>

#include "core/run_length_volume.h"

namespace soiq {

RunLengthVolume ball_dilation(const RunLengthVolume& structure, double radius_mm);

// The number of (dj, dk) offsets ball_dilation visits per line, for cost estimates.
int64_t ball_dilation_offsets(const ImageGeometry& grid, double radius_mm);

}  // namespace soiq
