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
  VoxelBox box = voxel_box(v);
  Mask m;
  m.geometry = v.geometry;
  if (box.empty) {
    m.geometry.dims = {0, 0, 0};
    return m;
  }
  if (v.geometry.uneven())
    box.lo[2] = std::max<int64_t>(box.lo[2] - 1, 0), box.hi[2] = std::min(box.hi[2] + 1, v.geometry.dims[2] - 1);
  m.geometry = sub_grid(v.geometry, box.lo, box.dims());
  m.voxels = box_mask(v, box);
  return m;
}

}  // namespace

Result<TriangleMesh> volume_surface(const RunLengthVolume& v) {
  const Mask mask = cropped_mask(v);
  if (mask.geometry.voxel_count() == 0) return TriangleMesh{};
  return marching_cubes(mask);
}

}  // namespace soiq::dicom
