#pragma once
// Distance between the centroid of a region's voxel centres and its intensity-weighted centroid
// (IBSI KLMA "centre of mass shift"; docs/DESIGN.md "Features").
//
// Inputs   region  the structure's voxels (the IBSI morphological and intensity masks are the same
//                  region here: no re-segmentation).
//          image   intensities on the same grid (check_same_grid), e.g. CT HU or PET SUV.
// Output   |c_geom - c_weighted| in mm, with c_geom = (1/N) sum p_n and
//          c_weighted = sum w_n p_n / sum w_n over the N inside voxels, p_n the LPS voxel centre
//          (direction matrix applied) and w_n the image value there.
// Errors   INVALID_ARGUMENT  grids differ, the image's voxel buffer does not match its grid, the
//                            region is empty or malformed, an inside value is not finite, or the
//                            inside values sum to 0 (no weighted centroid).
// Cost     O(runs + inside voxels), memory O(1). Thread-safe.
// Caveats  Negative intensities (CT) are used as they are, as IBSI does; with a sum near 0 the
//          weighted centroid is ill-conditioned. Images on another grid must be resampled first.

#include "core/base/image.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"

namespace soiq {

Result<double> centre_of_mass_shift_mm(const RunLengthVolume& region, const Image& image);

}  // namespace soiq
