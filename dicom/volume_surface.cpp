#include "dicom/volume_surface.h"

#include <algorithm>
#include <limits>

#include "core/io/marching_cubes.h"

namespace soiq::dicom {
namespace {

// The mask of `v` cropped to the bounding box of its voxels: marching cubes pads by one voxel of
// zeros anyway, so the surface is the same as on the full grid, at a fraction of the cost. On an
// unevenly spaced grid the box keeps one more slice of the grid on each side (where it has one),
// so that the surface between the outermost inside slices and their neighbours lies where the
// grid's slices are, not where the crop would extend its own.
Mask cropped_mask(const RunLengthVolume& v) {
  const auto& d = v.geometry.dims;
  int64_t lo[3] = {std::numeric_limits<int64_t>::max(), d[1], d[2]}, hi[3] = {-1, -1, -1};
  for (int64_t k = 0; k < d[2]; ++k)
    for (int64_t j = 0; j < d[1]; ++j) {
      const int64_t l = j + d[1] * k;
      if (v.line_start[l] == v.line_start[l + 1]) continue;
      lo[0] = std::min<int64_t>(lo[0], v.runs[v.line_start[l]].begin);
      hi[0] = std::max<int64_t>(hi[0], v.runs[v.line_start[l + 1] - 1].end - 1);
      lo[1] = std::min(lo[1], j), hi[1] = std::max(hi[1], j);
      lo[2] = std::min(lo[2], k), hi[2] = std::max(hi[2], k);
    }
  Mask m;
  m.geometry = v.geometry;
  if (hi[0] < 0) {
    m.geometry.dims = {0, 0, 0};
    return m;
  }
  if (v.geometry.uneven()) lo[2] = std::max<int64_t>(lo[2] - 1, 0), hi[2] = std::min(hi[2] + 1, d[2] - 1);
  m.geometry = sub_grid(v.geometry, {lo[0], lo[1], lo[2]}, {hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1});
  const auto& c = m.geometry.dims;
  m.voxels.assign(static_cast<size_t>(c[0] * c[1] * c[2]), 0);
  for (int64_t k = lo[2]; k <= hi[2]; ++k)
    for (int64_t j = lo[1]; j <= hi[1]; ++j) {
      const int64_t l = j + d[1] * k;
      uint8_t* row = m.voxels.data() + c[0] * ((j - lo[1]) + c[1] * (k - lo[2]));
      for (int64_t r = v.line_start[l]; r < v.line_start[l + 1]; ++r)
        std::fill(row + (v.runs[r].begin - lo[0]), row + (v.runs[r].end - lo[0]), uint8_t{1});
    }
  return m;
}

}  // namespace

Result<TriangleMesh> volume_surface(const RunLengthVolume& v) {
  const Mask mask = cropped_mask(v);
  if (mask.geometry.voxel_count() == 0) return TriangleMesh{};
  return marching_cubes(mask);
}

}  // namespace soiq::dicom
