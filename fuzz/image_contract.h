#pragma once
// What decode_image (core/io/read_image.h) promises of an image it returns, checked by the image
// harnesses on every success: a valid geometry (finite spacing > 0, orthonormal direction) and
// exactly one voxel per grid point. And the limits they decode under, like soiqd's: a voxel cap and a
// memory budget asked before any voxel is inflated (core/io/image_decode_limits.h), so an input
// that announces a huge image costs a header parse; a reader that allocates before asking shows
// as libFuzzer's out-of-memory.

#include <cstdint>

#include "core/base/image.h"
#include "core/io/image_decode_limits.h"
#include "fuzz/require.h"

namespace soiq::fuzz {

inline ImageDecodeLimits image_fuzz_limits() {
  ImageDecodeLimits limits;
  limits.max_voxels = int64_t(1) << 24;
  limits.before_decoding = [](const ImageGeometry&, int64_t decode_bytes) {
    constexpr int64_t kBudgetBytes = int64_t(256) << 20;
    return decode_bytes <= kBudgetBytes ? ok_status() : resource_exhausted("over the fuzzing budget");
  };
  return limits;
}

inline void check_image_contract(const Image& image) {
  require(validate_geometry(image.geometry).ok(), "decode_image returned an invalid geometry");
  require(int64_t(image.voxels.size()) == image.geometry.voxel_count(),
          "decode_image returned a voxel count other than the grid's");
}

}  // namespace soiq::fuzz
