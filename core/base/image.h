#pragma once
// Voxel data on an ImageGeometry, i fastest (index = i + nx * (j + ny * k)).
// `Image` holds intensities (CT in HU, PET in SUV, any label map); `Mask` is 0/1.

#include <cstdint>
#include <vector>

#include "core/base/image_geometry.h"

namespace soiq {

struct Image {
  ImageGeometry geometry;
  std::vector<float> voxels;
};

struct Mask {
  ImageGeometry geometry;
  std::vector<uint8_t> voxels;  // 0 outside, 1 inside
};

}  // namespace soiq
