#pragma once
// How two masks on the same grid agree: the paper's IoU and the number of differing voxels (the
// peers must match ours voxel for voxel before a time is reported).

#include <cstdint>

#include "core/base/image.h"
#include "core/base/status.h"

namespace soiq::bench {

struct Agreement {
  int64_t count_a = 0, count_b = 0;
  int64_t differing = 0;  // in a only + in b only
  double iou = 1;
};

// Through soiq::compare on RunLengthVolumes (from_mask); INVALID_ARGUMENT when the grids differ.
Result<Agreement> mask_agreement(const Mask& a, const Mask& b);

}  // namespace soiq::bench
