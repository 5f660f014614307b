#pragma once
// The values of an image at the voxel centres of a region given on another grid in the same frame
// of reference (docs/DESIGN.md "Features": intensity over an image series in the same frame of reference;
// each value taken at a voxel centre, by nearest neighbour or linear interpolation, as asked).
//
// Inputs
//   image          voxels on a valid geometry (LPS mm); voxels.size() == nx*ny*nz.
//   region         a RunLengthVolume on its own valid grid, in the same LPS frame as the image.
//   interpolation  kNearest: the value of the image voxel whose centre is nearest (ties round up,
//                  floor(c + 0.5) in continuous index c); kLinear: trilinear between the 8 image
//                  voxel centres around the point.
// Output
//   RegionSamples: one value per region voxel centre that lies inside the image, in run order. A
//   centre lies inside the image iff its continuous image index c satisfies -0.5 <= c <= n - 0.5 on
//   every axis (the image's voxels cover it; 1e-6 voxel of slack for geometry stored in float32).
//   Between the outermost image centres and that border, linear uses the border value (as nearest
//   does). Centres outside the image are excluded and counted in outside_image; centres where the
//   image value is NaN or infinite (any contributing neighbour, for linear) are excluded and counted
//   in non_finite. When the two grids are the same (check_same_grid), values are read directly
//   (same_grid = true) and the interpolation does not matter.
// Errors
//   INVALID_ARGUMENT  bad geometry of either; image voxel count differs from its grid; the region has
//                     no voxels ("region is empty"); no region voxel centre lies inside the image
//                     (message names the frame of reference: the usual cause is an image of another
//                     patient, study or registration).
// Cost
//   O(runs + region voxels); memory 8 bytes per sampled value. Thread-safe.
// Caveats
//   No partial-volume weighting: a region voxel samples the image at its centre only, so a region
//   on a much coarser grid than the image skips image voxels (use the finer grid for the region).

#include <cstdint>
#include <vector>

#include "core/base/coverage_volume.h"
#include "core/base/image.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"

namespace soiq {

enum class Interpolation { kNearest, kLinear };

// "nearest" or "linear", as stated in outputs.
const char* interpolation_name(Interpolation interpolation);

struct RegionSamples {
  std::vector<double> values;  // one per sampled region voxel centre, in run order
  int64_t region_voxels = 0;   // voxels in the region
  int64_t outside_image = 0;   // centres outside the image, excluded
  int64_t non_finite = 0;      // centres with a NaN or infinite image value, excluded
  Interpolation interpolation = Interpolation::kNearest;
  bool same_grid = false;  // read directly: the region and the image share one grid
};

Result<RegionSamples> resample(const Image& image, const RunLengthVolume& region, Interpolation interpolation);

// The same sampling at every voxel with coverage (coverage_volume.h), each value beside its
// voxel's fraction as its weight: per line, the wholly covered voxels (weight 1), then the partly
// covered ones. Voxels outside the image or non-finite there are left out of both (and counted).
// Errors as resample's, for the voxels with any coverage.
struct WeightedSamples {
  std::vector<double> values;
  std::vector<double> weights;  // in (0, 1], one per value
  int64_t region_voxels = 0, outside_image = 0, non_finite = 0;
};
Result<WeightedSamples> resample_weighted(const Image& image, const CoverageVolume& coverage,
                                          Interpolation interpolation);

}  // namespace soiq
