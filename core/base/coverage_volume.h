#pragma once
// How much of each voxel lies inside a surface (its partial volume, or coverage fraction), as the 1D
// method's coverage variant computes it (core/voxelize/coverage_1d.h; docs/DESIGN.md, "Coverage
// fractions"). Stored like a RunLengthVolume plus the boundary: per row line (j,k), the runs of
// voxels wholly inside (fraction exactly 1) and the partly covered voxels with their fraction in
// (0, 1). Every other voxel is wholly outside (exactly 0). Partly covered voxels lie along the
// surface, so the volume costs O(runs + surface voxels), never the dense grid.

#include <cstdint>
#include <vector>

#include "core/base/image.h"
#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"

namespace soiq {

struct PartialVoxel {
  int32_t i = 0;         // voxel index along the row
  float fraction = 0.f;  // in (0, 1): never exactly 0 or 1
  bool operator==(const PartialVoxel&) const = default;
};

struct CoverageVolume {
  ImageGeometry geometry;
  // n: the fractions sample n x n lines across each voxel (exact along the row). 1 = one line
  // through the voxel centre.
  int lines_per_voxel = 1;
  // Line l = j + ny * k: full[full_start[l] .. full_start[l+1]) are its wholly covered runs
  // (sorted, disjoint, non-adjacent), partial[partial_start[l] .. partial_start[l+1]) its partly
  // covered voxels in increasing i, none inside a full run. Both index arrays have ny*nz + 1 entries.
  std::vector<int64_t> full_start;
  std::vector<Run> full;
  std::vector<int64_t> partial_start;
  std::vector<PartialVoxel> partial;

  int64_t line_count() const { return geometry.dims[1] * geometry.dims[2]; }
};

// The sum of the fractions, in voxels (multiply by geometry.voxel_volume_mm3() for mm^3). O(runs +
// partial voxels), summed in double.
double covered_voxels(const CoverageVolume& v);

// The voxels whose fraction is >= `threshold` in (0, 1] (0.5: IBSI's binarisation of a fractional
// mask). O(runs + partial voxels).
RunLengthVolume threshold(const CoverageVolume& v, double threshold);

// The voxels wholly covered (fraction exactly 1) and those with any coverage (fraction > 0).
RunLengthVolume wholly_covered(const CoverageVolume& v);
RunLengthVolume any_coverage(const CoverageVolume& v);

// The dense fractions as float32 in [0, 1]. RESOURCE_EXHAUSTED over `max_voxels`. O(voxels).
Result<Image> to_fraction_image(const CoverageVolume& v, int64_t max_voxels = kDefaultMaxVoxels);

// The dense fractions as bytes: 0 exactly for wholly outside, 255 exactly for wholly inside, and
// round(255 f) clamped to 1..254 for a partly covered voxel, so 0 and 255 keep their exact meaning
// (a mask of uint8 0..255 rather than 0/1). RESOURCE_EXHAUSTED over `max_voxels`. O(voxels).
Result<Mask> to_fraction_bytes(const CoverageVolume& v, int64_t max_voxels = kDefaultMaxVoxels);

// The byte to_fraction_bytes gives a partly covered voxel of fraction f in (0, 1): round(255 f)
// clamped to 1..254. O(1).
uint8_t fraction_byte(float f);

// Bytes the volume holds as allocated. O(1).
int64_t coverage_bytes(const CoverageVolume& v);

}  // namespace soiq
