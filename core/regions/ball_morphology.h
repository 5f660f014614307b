#pragma once
// Dilation and erosion of a structure by a ball of radius r mm on its own grid, straight on the
// runs: the shell and core regions of regions.h without a dense box or a distance transform.
//   ball_dilation: a voxel is in the result iff its centre is within r mm of an inside voxel
//                  centre, each axis with its own spacing.
//   ball_erosion:  an inside voxel is in the result iff no outside voxel centre of the grid is
//                  within r mm of its centre. Voxels beyond the grid are not outside (regions.h:
//                  the grid is the world), so a structure touching the border is not eroded from
//                  that side.
//
// Inputs   structure  runs on a valid grid (checked by the caller, regions.h);
//          radius_mm  finite, > 0.
// Output   runs on the same grid, clipped to it. "Within" is decided exactly as regions.h's
//          distance transform decides it: for offsets (di, dj, dk) voxels, with d_a = offset_a x
//          spacing_a, the double value (dk)^2 + ((dj)^2 + (di)^2), each square and sum rounded, is
//          <= r^2 (1 + 1e-12). That value grows with |di|, so each (dj, dk) has a largest |di|.
// Cost     O(lines x (offsets (dj, dk) in the ball x runs per line + the line's reach)): each
//          line's pieces are counted in a difference array, no sort (a dilated voxel is covered
//          at least once, an eroded one by every neighbour line in the grid). Cheaper than the
//          distance transform's O(box voxels) while the ball's cross section is small next to the
//          box (regions.h chooses). Thread-safe.

#include <cstdint>

#include "core/base/run_length_volume.h"

namespace soiq {

RunLengthVolume ball_dilation(const RunLengthVolume& structure, double radius_mm);

RunLengthVolume ball_erosion(const RunLengthVolume& structure, double radius_mm);

// The number of (dj, dk) offsets either visits per line, for cost estimates; counting stops at
// `stop_at` (a huge ball on a large grid has hundreds of thousands).
int64_t ball_offset_lines(const ImageGeometry& grid, double radius_mm, int64_t stop_at);

}  // namespace soiq
