#pragma once
// What an image reader checks once it knows an image's grid and voxel type from its header, and
// before it inflates or decodes a single voxel: the grid's size against a voxel limit, then a
// caller's admission (soiqd reserves the decoding's peak bytes in its memory budget there). So a
// small file announcing a huge image costs a header parse, never the allocation.
//
// check_before_decoding
//   Inputs   the parsed geometry; the bytes per stored voxel; the limits; `name` for messages.
//   Errors   RESOURCE_EXHAUSTED over `max_voxels` (check_grid_size's message); whatever
//            `before_decoding` returns.
//   Cost     O(1) plus the callback.

#include <cstdint>
#include <functional>
#include <string>

#include "core/base/image_geometry.h"
#include "core/base/status.h"

namespace soiq {

struct ImageDecodeLimits {
  int64_t max_voxels = kDefaultMaxVoxels;
  // Called with the grid and the peak bytes decoding will hold (the decoded stored values plus the
  // float voxels); a non-OK status stops the read with that status.
  std::function<Status(const ImageGeometry& geometry, int64_t decode_bytes)> before_decoding;
};

inline Status check_before_decoding(const ImageGeometry& geometry, size_t stored_voxel_bytes,
                                    const ImageDecodeLimits& limits) {
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, limits.max_voxels));
  if (!limits.before_decoding) return ok_status();
  return limits.before_decoding(geometry, geometry.voxel_count() * int64_t(stored_voxel_bytes + sizeof(float)));
}

}  // namespace soiq
