#pragma once
// The inputs of the SEG export tests (tests/dicom/seg_export_*_test.cpp): an axis-aligned and an
// oblique grid, masks of shapes on them, a segment of a volume, the read-back of written bytes, and
// a valid source and segment that each bad-input test breaks in one way.

#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "dicom/read_seg.h"
#include "dicom/seg_export.h"
#include "dicom_test_support.h"
#include "seg_test_support.h"

namespace soiq::dicom::testing {

// Columns and rows chosen so that a frame is not a whole number of bytes (37 x 29 = 1073 bits): the
// bit-packed frames then start mid-byte, which the packing must get right.
inline ImageGeometry axis_aligned_grid() {
  ImageGeometry g;
  g.dims = {37, 29, 11};
  g.spacing_mm = {0.7, 1.3, 2.5};
  g.origin_mm = {-100.25, 30.5, -7.125};
  return g;
}

// Rotation by 30 degrees about (1, 2, 3)/|..|: every direction cosine is non-trivial.
inline ImageGeometry oblique_grid() {
  ImageGeometry g = axis_aligned_grid();
  const Vec3 a = (1.0 / std::sqrt(14.0)) * Vec3{1, 2, 3};
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col) {
      const double cross_term = (r == col) ? 0 : ((r + 1) % 3 == col ? -1 : 1) * a[3 - r - col] * s;
      g.direction[r][col] = (r == col ? c : 0) + (1 - c) * a[r] * a[col] + cross_term;
    }
  return g;
}

// A hollow ball (a shell: a hole inside), a box apart from it and scattered single voxels; slices 0
// and 7 stay empty so that frames are sparse.
inline Mask shapes(const ImageGeometry& g, uint32_t seed) {
  Mask m{g, std::vector<uint8_t>(static_cast<size_t>(g.voxel_count()), 0)};
  const int64_t nx = g.dims[0], ny = g.dims[1];
  auto at = [&](int64_t i, int64_t j, int64_t k) -> uint8_t& {
    return m.voxels[static_cast<size_t>(i + nx * (j + ny * k))];
  };
  for (int64_t k = 1; k < g.dims[2]; ++k) {
    if (k == 7) continue;
    for (int64_t j = 0; j < ny; ++j)
      for (int64_t i = 0; i < nx; ++i) {
        const double r2 = std::pow((i - 12) * 0.7, 2) + std::pow((j - 14) * 1.3, 2) + std::pow((k - 5) * 2.5, 2);
        if (r2 <= 8.0 * 8.0 && r2 >= 4.0 * 4.0) at(i, j, k) = 1;
        if (i >= 28 && i < 36 && j >= 3 && j < 9 && k >= 2 && k < 5) at(i, j, k) = 1;
      }
  }
  uint32_t x = seed;
  for (int n = 0; n < 40; ++n) {
    x = x * 1664525u + 1013904223u;
    const int64_t i = x % nx, j = (x / 64) % ny, k = 1 + (x / 4096) % (g.dims[2] - 1);
    if (k != 7) at(i, j, k) = 1;
  }
  return m;
}

inline SegSegment segment_of(const std::string& label, RunLengthVolume volume) {
  SegSegment s;
  s.label = label;
  s.volume = std::move(volume);
  return s;
}

// read_seg_file on `bytes` saved to a temp file: read_seg reads only files (dicom/read_seg.h).
inline Result<SegObject> read_back(const std::string& bytes, const ImageGeometry& g) {
  TempDir tmp;
  const std::string path = tmp.file("seg.dcm");
  std::ofstream(path, std::ios::binary) << bytes;
  return read_seg_file(path, g);
}

// A valid source and segment; each bad-input test changes one thing.
struct BadInput {
  SegSource source = synthetic_source(axis_aligned_grid());
  SegSegment segment = segment_of("GTV", from_mask(shapes(axis_aligned_grid(), 1)));
};

}  // namespace soiq::dicom::testing
