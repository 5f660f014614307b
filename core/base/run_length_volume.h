#pragma once
// A volume model as the 1D method produces it (docs/DESIGN.md, "The 1D method, precisely"): for every
// row line (j,k) of a grid, the sorted, disjoint, non-adjacent half-open runs [begin, end) of
// voxel indices i that are inside. Canonical: two RunLengthVolumes hold the same voxels iff their
// runs are equal, so comparison is exact and cheap.

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/image.h"
#include "core/base/image_geometry.h"
#include "core/base/status.h"

namespace soiq {

struct Run {
  int32_t begin = 0;  // first inside voxel index i
  int32_t end = 0;    // one past the last; begin < end
  bool operator==(const Run&) const = default;
};

struct RunLengthVolume {
  ImageGeometry geometry;
  // Runs of line (j,k) are runs[line_start[l]] .. runs[line_start[l+1]-1], l = j + ny * k.
  // line_start has ny*nz + 1 entries.
  std::vector<int64_t> line_start;
  std::vector<Run> runs;

  int64_t line_count() const { return geometry.dims[1] * geometry.dims[2]; }
};

// An empty volume (no runs) on `g`.
RunLengthVolume empty_volume(const ImageGeometry& g);

// Number of inside voxels. O(runs).
int64_t voxel_count(const RunLengthVolume& v);

// The bytes the volume holds (its line index and runs, as allocated). O(1).
int64_t run_length_bytes(const RunLengthVolume& v);

// The dense 0/1 mask, filled by `threads` threads over slices. RESOURCE_EXHAUSTED when the grid
// exceeds `max_voxels`. O(voxels).
Result<Mask> to_mask(const RunLengthVolume& v, int64_t max_voxels = kDefaultMaxVoxels, int threads = 1);

// Fills `out` (nx*ny*nz bytes, zeroed by the caller) with 1 for inside voxels. O(runs + inside).
void fill_dense(const RunLengthVolume& v, uint8_t* out);

// Inclusive index bounds of a volume's inside voxels; `empty` when there are none. O(lines).
struct VoxelBox {
  std::array<int64_t, 3> lo{0, 0, 0}, hi{-1, -1, -1};
  bool empty = true;
  std::array<int64_t, 3> dims() const { return {hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1}; }
};
VoxelBox voxel_box(const RunLengthVolume& v);

// The inside voxels of `box` as 0/1 bytes, i fastest over the box (box.dims() voxels; zero where
// the box reaches beyond the grid, as a padded box does). The caller bounds the box's size.
// O(box voxels).
std::vector<uint8_t> box_mask(const RunLengthVolume& v, const VoxelBox& box);

// Runs of the nonzero voxels of a dense mask. O(voxels).
RunLengthVolume from_mask(const Mask& m);

// Overlap of two volumes on the same grid (the paper's IoU measure and friends).
struct VolumeComparison {
  int64_t count_a = 0, count_b = 0;
  int64_t intersection = 0;
  int64_t only_a = 0, only_b = 0;  // differing voxels = only_a + only_b
  double iou() const;              // |A∩B| / |A∪B|; 1 when both are empty
  double dice() const;             // 2|A∩B| / (|A|+|B|); 1 when both are empty
};
// INVALID_ARGUMENT when the grids differ (check_same_grid). O(runs).
Result<VolumeComparison> compare(const RunLengthVolume& a, const RunLengthVolume& b);

}  // namespace soiq
