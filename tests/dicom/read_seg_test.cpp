// Reading DICOM SEG files (dicom/read_seg.h): a SEG packed by another tool as PS3.5 says (frames'
// bits back to back) reads exactly as pydicom decodes it, and hostile SEGs (no frames, truncated
// Pixel Data, no rows, wrong bit depth, frame counts that disagree) are INVALID_ARGUMENT with a
// message that says what is wrong, before any pixel is read.
#include "dicom/read_seg.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <functional>
#include <vector>

#include "core/base/run_length_volume.h"
#include "dicom/seg_export.h"
#include "dicom_test_support.h"
#include "seg_test_support.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;
using testing::TempDir;

// The grid of tests/data/dicom/standard_seg.dcm (make_standard_seg.py beside it).
ImageGeometry standard_seg_grid() {
  ImageGeometry g;
  g.dims = {11, 7, 6};
  g.spacing_mm = {0.9, 1.2, 3.0};
  g.origin_mm = {10.0, -5.5, 20.0};
  return g;
}

TEST(ReadSeg, StandardPackedThirdPartySegReadsExactlyAsPydicomDecodesIt) {
  const std::string path = data_dir("dicom/standard_seg.dcm");
  const ImageGeometry grid = standard_seg_grid();
  auto seg = read_seg_file(path, grid);
  ASSERT_TRUE(seg.ok()) << seg.status().to_string();
  ASSERT_EQ(seg->segments.size(), 2u);
  EXPECT_EQ(seg->segments[0].label, "disc");
  EXPECT_EQ(seg->segments[1].label, "ring");
  // Frames in file order: segment 2 on k = 4, 1, 2, 5 and segment 1 on k = 0, 3, 1, 5.
  EXPECT_EQ(seg->segments[0].frames.size(), 4u);
  EXPECT_EQ(seg->segments[1].frames.size(), 4u);
  EXPECT_EQ(seg->segments[1].frames[0].k, 4);

  TempDir tmp;
  const std::vector<Mask> pydicom = testing::pydicom_segments(path, grid, 2, tmp);
  ASSERT_EQ(pydicom.size(), 2u);
  for (size_t s = 0; s < 2; ++s)
    testing::expect_same_as_pydicom(seg->segments[s].volume, pydicom[s], "segment " + std::to_string(s + 1));
  // Recorded from pydicom (ds.pixel_array.sum() over each segment's frames), in case both drift.
  EXPECT_EQ(voxel_count(seg->segments[0].volume), 22 + 22 + 22 + 22);
  EXPECT_EQ(voxel_count(seg->segments[1].volume), 20 + 22 + 20 + 21);
}

// --- hostile SEGs: a valid SEG of ours, edited with DCMTK and saved to a file ---

ImageGeometry small_grid() {
  ImageGeometry g;
  g.dims = {13, 9, 4};  // 117 pixels a frame: frames start mid-byte
  g.spacing_mm = {0.8, 1.1, 2.0};
  return g;
}

// Writes a SEG of one segment on small_grid (3 frames), applies `edit` to its dataset, saves it.
std::string hostile_seg(const TempDir& tmp, const std::function<void(DcmDataset&)>& edit) {
  const ImageGeometry g = small_grid();
  Mask m{g, std::vector<uint8_t>(static_cast<size_t>(g.voxel_count()), 0)};
  for (size_t n = 0; n < m.voxels.size(); n += 3)
    if (static_cast<int64_t>(n) / (g.dims[0] * g.dims[1]) != 2) m.voxels[n] = 1;  // slices 0, 1, 3
  SegSegment s;
  s.label = "GTV";
  s.volume = from_mask(m);
  auto written = write_seg(testing::synthetic_source(g), {s});
  EXPECT_TRUE(written.ok()) << written.status().to_string();
  const std::string path = tmp.file("hostile.dcm");
  std::ofstream(path, std::ios::binary) << written->bytes;
  DcmFileFormat file;
  EXPECT_TRUE(file.loadFile(path.c_str()).good());
  edit(*file.getDataset());
  EXPECT_TRUE(file.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
  return path;
}

void expect_invalid(const Result<SegObject>& r, const std::string& phrase) {
  ASSERT_FALSE(r.ok()) << "accepted";
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  EXPECT_NE(r.status().message().find(phrase), std::string::npos) << r.status().to_string();
}

TEST(ReadSeg, UneditedHostileBaseReadsBack) {
  TempDir tmp;
  auto r = read_seg_file(hostile_seg(tmp, [](DcmDataset&) {}), small_grid());
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->segments.at(0).frames.size(), 3u);
}

TEST(ReadSeg, ZeroFramesIsInvalidArgumentNotACrash) {
  TempDir tmp;
  const std::string path =
      hostile_seg(tmp, [](DcmDataset& ds) { ASSERT_TRUE(ds.putAndInsertString(DCM_NumberOfFrames, "0").good()); });
  expect_invalid(read_seg_file(path, small_grid()),
                 "SEG '" + path + "' has NumberOfFrames '0'; a SEG needs at least 1 frame");
}

TEST(ReadSeg, MissingNumberOfFramesIsInvalidArgument) {
  TempDir tmp;
  const std::string path = hostile_seg(tmp, [](DcmDataset& ds) { ds.findAndDeleteElement(DCM_NumberOfFrames); });
  expect_invalid(read_seg_file(path, small_grid()), "has NumberOfFrames ''");
}

TEST(ReadSeg, TruncatedPixelDataIsInvalidArgumentSayingWhatIsMissing) {
  TempDir tmp;
  // 3 frames x 9 x 13 = 351 bits need 44 bytes; 20 are left.
  const std::string path = hostile_seg(tmp, [](DcmDataset& ds) {
    const Uint8* bytes = nullptr;
    unsigned long count = 0;
    ASSERT_TRUE(ds.findAndGetUint8Array(DCM_PixelData, bytes, &count).good());
    ASSERT_EQ(count, 44u);
    const std::vector<Uint8> head(bytes, bytes + 20);
    ASSERT_TRUE(ds.putAndInsertUint8Array(DCM_PixelData, head.data(), 20).good());
  });
  expect_invalid(
      read_seg_file(path, small_grid()),
      "SEG '" + path + "' is truncated: 20 bytes of pixel data, NumberOfFrames 3 x Rows 9 x Columns 13 needs 44");
}

TEST(ReadSeg, MissingPixelDataIsInvalidArgument) {
  TempDir tmp;
  const std::string path = hostile_seg(tmp, [](DcmDataset& ds) { ds.findAndDeleteElement(DCM_PixelData); });
  expect_invalid(read_seg_file(path, small_grid()), "has no Pixel Data");
}

TEST(ReadSeg, ZeroRowsIsInvalidArgument) {
  TempDir tmp;
  const std::string path =
      hostile_seg(tmp, [](DcmDataset& ds) { ASSERT_TRUE(ds.putAndInsertUint16(DCM_Rows, 0).good()); });
  expect_invalid(read_seg_file(path, small_grid()), "has frames of Rows 0 x Columns 13; each needs at least 1");
}

TEST(ReadSeg, EightBitsAllocatedInABinarySegIsInvalidArgument) {
  TempDir tmp;
  const std::string path =
      hostile_seg(tmp, [](DcmDataset& ds) { ASSERT_TRUE(ds.putAndInsertUint16(DCM_BitsAllocated, 8).good()); });
  expect_invalid(read_seg_file(path, small_grid()), "has Bits Allocated 8; a BINARY segmentation has 1 bit per pixel");
}

TEST(ReadSeg, FractionalSegIsInvalidArgument) {
  TempDir tmp;
  const std::string path = hostile_seg(tmp, [](DcmDataset& ds) {
    ASSERT_TRUE(ds.putAndInsertString(DCM_SegmentationType, "FRACTIONAL").good());
    ASSERT_TRUE(ds.putAndInsertUint16(DCM_BitsAllocated, 8).good());
  });
  expect_invalid(read_seg_file(path, small_grid()), "FRACTIONAL segmentation; only BINARY ones are read");
}

// Frame counts are refused before anything is sized by them: beyond what a Pixel Data can hold by
// the count alone, below that by the length check.
TEST(ReadSeg, HugeFrameCountsAreInvalidArgumentWithoutAllocating) {
  TempDir tmp;
  const std::string beyond = hostile_seg(
      tmp, [](DcmDataset& ds) { ASSERT_TRUE(ds.putAndInsertString(DCM_NumberOfFrames, "2147483647").good()); });
  expect_invalid(read_seg_file(beyond, small_grid()),
                 "claims NumberOfFrames 2147483647 of Rows 9 x Columns 13, more pixels than a Pixel Data can hold");
  const std::string many = hostile_seg(
      tmp, [](DcmDataset& ds) { ASSERT_TRUE(ds.putAndInsertString(DCM_NumberOfFrames, "1000000").good()); });
  expect_invalid(read_seg_file(many, small_grid()),
                 "is truncated: 44 bytes of pixel data, NumberOfFrames 1000000 x Rows 9 x Columns 13 needs 14625000");
}

// More frames claimed than there are Per-Frame Functional Groups items (the Pixel Data long enough).
TEST(ReadSeg, FrameCountOtherThanPerFrameItemsIsInvalidArgument) {
  TempDir tmp;
  const std::string path = hostile_seg(tmp, [](DcmDataset& ds) {
    ASSERT_TRUE(ds.putAndInsertString(DCM_NumberOfFrames, "4").good());
    const std::vector<Uint8> zeros(60, 0);
    ASSERT_TRUE(ds.putAndInsertUint8Array(DCM_PixelData, zeros.data(), 60).good());
  });
  expect_invalid(read_seg_file(path, small_grid()), "3 Per-Frame Functional Groups items but NumberOfFrames 4");
}

}  // namespace
}  // namespace soiq::dicom
