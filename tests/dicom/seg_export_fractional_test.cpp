// write_fractional_seg (dicom/seg_export_fractional.h): a ball's coverage fractions on an oblique
// grid written as a FRACTIONAL SEG, read back with DCMTK byte for byte against to_fraction_bytes,
// checked by dciodvfy, and its bad inputs refused.
#include "dicom/seg_export_fractional.h"

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/geometry/primitives.h"
#include "core/voxelize/coverage_1d.h"
#include "seg_export_fixture.h"

namespace soiq::dicom::testing {
namespace fractional_seg_test {

// A ball of radius 6 mm on the oblique grid (37 x 29 x 11 voxels), 3 x 3 lines per voxel.
CoverageVolume ball_coverage() {
  const ImageGeometry g = oblique_grid();
  const Vec3 centre = g.index_to_physical({18, 14, 5});
  CoverageOptions options;
  options.lines_per_voxel = 3;
  Result<CoverageVolume> c = coverage_1d(uv_sphere(centre, 6, 24, 48), g, options);
  EXPECT_TRUE(c.ok()) << c.status().to_string();
  return c.ok() ? std::move(*c) : CoverageVolume{};
}

FractionalSegSegment fractional_segment(CoverageVolume c) {
  FractionalSegSegment s;
  s.label = "ball";
  s.coverage = std::move(c);
  return s;
}

std::string saved(const std::string& bytes, const TempDir& tmp) {
  const std::string path = tmp.file("fractional.dcm");
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

}  // namespace fractional_seg_test

using namespace fractional_seg_test;

TEST(FractionalSegExport, FramesHoldTheFractionBytesOfEachCoveredSlice) {
  const CoverageVolume coverage = ball_coverage();
  const ImageGeometry& g = coverage.geometry;
  Result<WrittenSeg> written = write_fractional_seg(synthetic_source(g), {fractional_segment(coverage)});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  Result<Mask> want = to_fraction_bytes(coverage);
  ASSERT_TRUE(want.ok());
  TempDir tmp;
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(saved(written->bytes, tmp).c_str()).good());
  DcmDataset& ds = *file.getDataset();
  OFString type, fractional_type;
  Uint16 max_value = 0, bits = 0, stored = 0, high = 0;
  ds.findAndGetOFString(DCM_SegmentationType, type);
  ds.findAndGetOFString(DCM_SegmentationFractionalType, fractional_type);
  ds.findAndGetUint16(DCM_MaximumFractionalValue, max_value);
  ds.findAndGetUint16(DCM_BitsAllocated, bits);
  ds.findAndGetUint16(DCM_BitsStored, stored);
  ds.findAndGetUint16(DCM_HighBit, high);
  EXPECT_EQ(type, "FRACTIONAL");
  EXPECT_EQ(fractional_type, "OCCUPANCY");
  EXPECT_EQ(max_value, 255);
  EXPECT_EQ(bits, 8);
  EXPECT_EQ(stored, 8);
  EXPECT_EQ(high, 7);
  // Frames are the slices with any coverage, in k order (one segment).
  const size_t slice_bytes = size_t(g.dims[0] * g.dims[1]);
  std::vector<int64_t> covered;
  for (int64_t k = 0; k < g.dims[2]; ++k) {
    const auto first = want->voxels.begin() + std::ptrdiff_t(slice_bytes * size_t(k));
    if (std::any_of(first, first + std::ptrdiff_t(slice_bytes), [](uint8_t b) { return b != 0; })) covered.push_back(k);
  }
  ASSERT_EQ(written->frame_count, int64_t(covered.size()));
  ASSERT_LT(covered.size(), size_t(g.dims[2])) << "the ball should leave slices empty";
  const Uint8* pixels = nullptr;
  unsigned long length = 0;
  ASSERT_TRUE(ds.findAndGetUint8Array(DCM_PixelData, pixels, &length).good());
  ASSERT_GE(length, covered.size() * slice_bytes);
  int64_t differing = 0, partial = 0;
  for (size_t f = 0; f < covered.size(); ++f)
    for (size_t p = 0; p < slice_bytes; ++p) {
      const uint8_t got = pixels[f * slice_bytes + p];
      differing += got != want->voxels[slice_bytes * size_t(covered[f]) + p];
      partial += got > 0 && got < 255;
    }
  EXPECT_EQ(differing, 0);
  EXPECT_GT(partial, 0);
}

TEST(FractionalSegExport, DciodvfyFindsNoErrorOrWarning) {
  const CoverageVolume coverage = ball_coverage();
  Result<WrittenSeg> written =
      write_fractional_seg(synthetic_source(coverage.geometry), {fractional_segment(coverage)});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  TempDir tmp;
  int status = 0;
  const std::string all = run_command("dciodvfy " + saved(written->bytes, tmp), status);
  ASSERT_NE(all.find("Segmentation"), std::string::npos) << "dciodvfy did not run (Debian dicom3tools):\n" << all;
  std::istringstream lines(all);
  for (std::string line; std::getline(lines, line);)
    if (line.find("Error") != std::string::npos || line.find("Warning") != std::string::npos) ADD_FAILURE() << line;
}

TEST(FractionalSegExport, ACoverageWithNothingCoveredIsRefused) {
  CoverageVolume empty = ball_coverage();
  std::fill(empty.full_start.begin(), empty.full_start.end(), 0);
  std::fill(empty.partial_start.begin(), empty.partial_start.end(), 0);
  empty.full.clear();
  empty.partial.clear();
  Result<WrittenSeg> r = write_fractional_seg(synthetic_source(empty.geometry), {fractional_segment(empty)});
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("structure 'ball' has no voxels"), std::string::npos) << r.status().message();
}

TEST(FractionalSegExport, AMalformedCoverageIsRefused) {
  CoverageVolume bad = ball_coverage();
  bad.partial_start.pop_back();
  Result<WrittenSeg> r = write_fractional_seg(synthetic_source(bad.geometry), {fractional_segment(bad)});
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("malformed coverage volume"), std::string::npos) << r.status().message();
}

TEST(FractionalSegExport, ACoverageOnAnotherGridIsRefused) {
  CoverageVolume c = ball_coverage();
  Result<WrittenSeg> r = write_fractional_seg(synthetic_source(axis_aligned_grid()), {fractional_segment(c)});
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("is not on the source series grid"), std::string::npos) << r.status().message();
}

}  // namespace soiq::dicom::testing
