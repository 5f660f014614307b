#pragma once
// One row line of a coverage volume (coverage_1d.h): where each of the n x n sample lines through
// its voxels is inside the surface -> the voxels wholly covered and the fraction of the others.
// Internal to core/voxelize; pure, so tests can feed it intervals they know the answer for.

#include <cstdint>
#include <vector>

#include "core/base/coverage_volume.h"
#include "core/base/fill_rule.h"

namespace soiq {

// A sample line crossing the surface at x (continuous index along the row; voxel i spans
// [i - 1/2, i + 1/2)), entering (+1: normal against the line) or leaving (-1).
struct SampleCrossing {
  double x;
  int32_t sign;
};

// Where a sample line starts (+1) or stops (-1) being inside.
struct CoverageEvent {
  double x;
  int32_t delta;
};

// Sorts one sample line's crossings by x and appends to `events` a +1 where the line becomes inside
// under `rule` and a -1 where it stops. Returns false when the crossings do not balance (the
// surface is open along this line); the events of a balanced prefix are kept.
// Cost: O(c log c) for c crossings.
bool sample_line_events(SampleCrossing* first, SampleCrossing* last, FillRule rule, std::vector<CoverageEvent>& events);

// Sorts `events` (all sample lines of one row, `samples` = n*n of them) and appends the row's
// wholly covered runs to `full` (merging touching runs from `line_first_full` on) and its partly
// covered voxels to `partial`. A voxel's fraction is the inside length of its sample lines over
// their total length, both accumulated from the pieces between events, so a voxel no sample line
// leaves is exactly 1 (no piece outside) and one none enters exactly 0. Events outside the row are
// clamped to it. Cost: O(e log e + voxels partly covered by a run of the row).
void cover_line(std::vector<CoverageEvent>& events, int64_t nx, int samples, int64_t line_first_full,
                std::vector<Run>& full, std::vector<PartialVoxel>& partial);

}  // namespace soiq
