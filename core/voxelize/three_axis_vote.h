#pragma once
// The robust mode's vote (docs/DESIGN.md step 6, the paper's multi-ray score): three line fills of one
// grid, along i, j and k, combined so a voxel is inside when at least two of them say so.

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"

namespace soiq {

// The runs of a fill along `axis`: lines are indexed cyclically, so for axis a the runs lie along
// axis a and line l = index(a+1) + dims[a+1] * index(a+2).
struct AxisRuns {
  std::vector<int64_t> line_start;
  std::vector<Run> runs;
};

// Input  fills[a] for a = 0, 1, 2 on grid `g` (as voxelize_1d's scans produce them).
// Output the voxels inside in at least two fills, as runs along i.
// Cost   O(voxels) time and one byte per voxel (a dense vote count).
RunLengthVolume three_axis_vote(const ImageGeometry& g, const std::array<AxisRuns, 3>& fills);

}  // namespace soiq
