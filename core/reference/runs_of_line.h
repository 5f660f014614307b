#pragma once
// The runs of one row line of a dense 0/1 row, for the reference methods (core/reference/), which
// decide voxel by voxel and then store the result as a RunLengthVolume.
//
// Inputs   inside: `nx` flags (nonzero = inside), i = 0 .. nx-1.
// Output   the maximal half-open runs [begin, end) of nonzero flags, in increasing order.
// Cost     O(nx); thread-safe.

#include <cstdint>
#include <vector>

#include "core/base/run_length_volume.h"

namespace soiq {

std::vector<Run> runs_of_line(const uint8_t* inside, int64_t nx);

}  // namespace soiq
