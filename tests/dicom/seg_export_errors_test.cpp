// DICOM SEG export (dicom/seg_export.h) and read-back (dicom/read_seg.h) of bad inputs: each is
// refused with the code and a message that says why. The inputs are in seg_export_fixture.h.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "dicom/read_seg.h"
#include "dicom/seg_export.h"
#include "dicom_test_support.h"
#include "seg_export_fixture.h"

namespace soiq::dicom {
namespace {

using testing::axis_aligned_grid;
using testing::BadInput;
using testing::data_dir;
using testing::oblique_grid;
using testing::read_back;

SegWriteOptions max_frames(int64_t n) {
  SegWriteOptions o;
  o.max_frames = n;
  return o;
}

void expect_error(const Result<WrittenSeg>& r, StatusCode code, const std::string& phrase) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), code) << r.status().to_string();
  EXPECT_NE(r.status().message().find(phrase), std::string::npos) << r.status().to_string();
}

TEST(SegExport, VolumeOnAnotherGridIsInvalidArgument) {
  BadInput in;
  ImageGeometry other = axis_aligned_grid();
  other.spacing_mm[2] = 3.0;
  in.segment.volume.geometry = other;
  expect_error(write_seg(in.source, {in.segment}), StatusCode::kInvalidArgument, "not on the source series grid");
}

TEST(SegExport, EmptyVolumeIsInvalidArgumentNamingTheStructure) {
  BadInput in;
  in.segment.volume = empty_volume(axis_aligned_grid());
  expect_error(write_seg(in.source, {in.segment}), StatusCode::kInvalidArgument, "structure 'GTV' has no voxels");
}

TEST(SegExport, WrongSliceUidCountIsInvalidArgument) {
  BadInput in;
  in.source.slice_sop_instance_uids.pop_back();
  expect_error(write_seg(in.source, {in.segment}), StatusCode::kInvalidArgument,
               "10 slice SOP instance uids but its grid has 11 slices");
}

TEST(SegExport, EmptyLabelIsInvalidArgument) {
  BadInput in;
  in.segment.label = "";
  expect_error(write_seg(in.source, {in.segment}), StatusCode::kInvalidArgument, "empty label");
}

TEST(SegExport, MissingFrameOfReferenceIsInvalidArgument) {
  BadInput in;
  in.source.frame_of_reference_uid = "";
  expect_error(write_seg(in.source, {in.segment}), StatusCode::kInvalidArgument, "no frame of reference uid");
}

TEST(SegExport, TooManyFramesIsResourceExhausted) {
  BadInput in;
  expect_error(write_seg(in.source, {in.segment}, max_frames(3)), StatusCode::kResourceExhausted,
               "over the limit of 3");
}

TEST(SegRead, NonSegDicomIsInvalidArgument) {
  auto r = read_seg_file(data_dir("dicom/CT_small.dcm"), axis_aligned_grid());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  EXPECT_NE(r.status().message().find("not a DICOM Segmentation"), std::string::npos) << r.status().to_string();
}

TEST(SegRead, MissingFileIsNotFound) {
  auto r = read_seg_file(data_dir("dicom/no_such_seg.dcm"), axis_aligned_grid());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound) << r.status().to_string();
}

TEST(SegRead, GarbageBytesAreRefused) {
  std::string garbage(4096, '\0');
  uint32_t x = 7;
  for (char& c : garbage) c = static_cast<char>((x = x * 1103515245u + 12345u) >> 24);
  auto r = read_back(garbage, axis_aligned_grid());
  ASSERT_FALSE(r.ok());
  EXPECT_TRUE(r.status().code() == StatusCode::kDataLoss || r.status().code() == StatusCode::kInvalidArgument)
      << r.status().to_string();
}

TEST(SegRead, FrameOffTheGridSlicesIsInvalidArgumentNamingTheFrame) {
  BadInput in;
  auto written = write_seg(in.source, {in.segment});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  ImageGeometry shifted = axis_aligned_grid();
  shifted.origin_mm[2] += 0.5 * shifted.spacing_mm[2];  // frames now fall between slices
  auto r = read_back(written->bytes, shifted);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  EXPECT_NE(r.status().message().find("SEG frame 1:"), std::string::npos) << r.status().to_string();
  EXPECT_NE(r.status().message().find("not on a slice"), std::string::npos) << r.status().to_string();
}

TEST(SegRead, OtherOrientationIsInvalidArgument) {
  BadInput in;
  auto written = write_seg(in.source, {in.segment});
  ASSERT_TRUE(written.ok()) << written.status().to_string();
  ImageGeometry rotated = oblique_grid();
  auto r = read_back(written->bytes, rotated);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  EXPECT_NE(r.status().message().find("row direction"), std::string::npos) << r.status().to_string();
}

}  // namespace
}  // namespace soiq::dicom
