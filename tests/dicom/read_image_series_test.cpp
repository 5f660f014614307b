// Image series -> soiq::Image: the geometry the READMEs state, rescaled values, PET SUV, and the
// series it must refuse.
#include "dicom/read_image_series.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "core/io/read_image.h"
#include "ct_slice_writer.h"
#include "dicom/scan_dicom.h"
#include "dicom_test_support.h"

namespace soiq::dicom {
namespace {

using testing::data_dir;
namespace fs = std::filesystem;

Result<SeriesImage> read_only_series(const std::string& path, const std::string& modality) {
  auto s = scan_dicom({path});
  if (!s.ok()) return s.status();
  for (const auto& series : s->series)
    if (series.modality == modality) return read_image_series(series);
  return not_found("no " + modality + " series under " + path);
}

TEST(ReadImageSeries, CtSmallHasItsGeometryAndHounsfieldUnits) {
  auto r = read_only_series(data_dir("dicom/CT_small.dcm"), "CT");
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  const ImageGeometry& g = r->image.geometry;
  EXPECT_EQ(g.dims, (std::array<int64_t, 3>{128, 128, 1}));
  EXPECT_EQ(g.spacing_mm, (Vec3{0.661468, 0.661468, 5}));  // one slice: Slice Thickness
  EXPECT_EQ(g.origin_mm, (Vec3{-158.135803, -179.035797, -75.699997}));
  EXPECT_EQ(g.direction, identity3());
  EXPECT_EQ(r->units, "HU");
  // Stored values (signed 16 bit) read independently, plus the intercept -1024.
  DcmFileFormat f;
  ASSERT_TRUE(f.loadFile(data_dir("dicom/CT_small.dcm").c_str()).good());
  const Uint16* raw = nullptr;
  ASSERT_TRUE(f.getDataset()->findAndGetUint16Array(DCM_PixelData, raw).good());
  for (size_t i : {size_t{0}, size_t{777}, size_t{128 * 64 + 64}})
    EXPECT_EQ(r->image.voxels[i], static_cast<float>(static_cast<int16_t>(raw[i]) - 1024)) << i;
}

TEST(ReadImageSeries, MrSmallHasItsGeometry) {
  auto r = read_only_series(data_dir("dicom/MR_small.dcm"), "MR");
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->image.geometry.dims, (std::array<int64_t, 3>{64, 64, 1}));
  EXPECT_EQ(r->image.geometry.spacing_mm, (Vec3{0.3125, 0.3125, 0.8}));
  EXPECT_EQ(r->image.geometry.origin_mm, (Vec3{-83.9063, -91.2, 6.6406}));
  EXPECT_EQ(r->units, "");
}

TEST(ReadImageSeries, RtUtilsCtTakesSliceSpacingFromItsTwoPositions) {
  auto r = read_only_series(data_dir("dicom/rt-utils"), "CT");
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->image.geometry.dims, (std::array<int64_t, 3>{512, 512, 2}));
  EXPECT_EQ(r->image.geometry.spacing_mm, (Vec3{0.488281, 0.488281, 5}));
  EXPECT_EQ(r->image.geometry.origin_mm, (Vec3{-125, -125, 60}));
}

TEST(ReadImageSeries, StsPetIsSuvAndEqualsTheShippedNiftiImage) {
  auto r = read_only_series(data_dir("sts/STS_002/dicom/PET"), "PT");
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->units, "SUVbw");  // Units GML: stored as SUV body weight
  EXPECT_EQ(r->units_note, "");
  auto nifti = read_image(data_dir("sts/STS_002/PET_image.nii.gz"));
  ASSERT_TRUE(nifti.ok()) << nifti.status().to_string();
  const Status same = check_same_grid(r->image.geometry, nifti->geometry);
  ASSERT_TRUE(same.ok()) << same.to_string();
  ASSERT_EQ(r->image.voxels.size(), nifti->voxels.size());
  double worst = 0;
  for (size_t i = 0; i < r->image.voxels.size(); ++i)
    worst = std::max(worst, static_cast<double>(std::abs(r->image.voxels[i] - nifti->voxels[i])));
  // Both are float32 roundings of slope x stored value (slopes ~6e-4 SUV per unit, values < 20).
  EXPECT_LT(worst, 1e-5);
}

TEST(ReadImageSeries, StsCtSortsItsFortyEightSlices) {
  auto r = read_only_series(data_dir("sts/STS_002/dicom/CT"), "CT");
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->image.geometry.dims[2], 48);
  auto nifti = read_image(data_dir("sts/STS_002/CT_mask.nii.gz"));
  ASSERT_TRUE(nifti.ok());
  EXPECT_TRUE(check_same_grid(r->image.geometry, nifti->geometry).ok());
  EXPECT_EQ(r->slice_sop_instance_uids.size(), 48u);
  for (int k = 0; k + 1 < 48; ++k) {
    const double z0 = r->image.geometry.index_to_physical({0, 0, double(k)})[2];
    EXPECT_LT(z0, r->image.geometry.index_to_physical({0, 0, double(k + 1)})[2]);
  }
}

TEST(ReadImageSeries, MissingSliceIsReportedWithItsNeighbours) {
  testing::TempDir dir;
  const fs::path src = data_dir("sts/STS_002/dicom/PET/image");
  for (const auto& e : fs::directory_iterator(src)) fs::copy_file(e.path(), dir.path() / e.path().filename());
  auto full = scan_dicom({dir.path().string()});
  ASSERT_TRUE(full.ok());
  ASSERT_EQ(full->series.size(), 1u);
  // Drop the file of the 20th slice along the normal.
  auto image = read_image_series(full->series[0]);
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  const std::string dropped = image->slice_paths[20];
  fs::remove(dropped);
  auto gap = scan_dicom({dir.path().string()});
  ASSERT_TRUE(gap.ok());
  auto r = read_image_series(gap->series[0]);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("1 missing slice(s) between"), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find(image->slice_paths[19]), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find(image->slice_paths[21]), std::string::npos) << r.status().message();
}

TEST(ReadImageSeries, GridOverTheLimitIsResourceExhausted) {
  auto s = scan_dicom({data_dir("dicom/CT_small.dcm")});
  ASSERT_TRUE(s.ok());
  auto r = read_image_series(s->series[0], /*max_voxels=*/1000);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted);
}

TEST(ReadImageSeries, ImagesWithoutPositionAreRefusedNamingTheFile) {
  auto s = scan_dicom({data_dir("dicom/dicomdirtests/77654033/CR1")});  // a radiograph: no IPP
  ASSERT_TRUE(s.ok());
  ASSERT_EQ(s->series.size(), 1u);
  auto r = read_image_series(s->series[0]);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("CR1"), std::string::npos) << r.status().message();
}

// A header the pixels or the grid cannot honour: one behaviour (refused before any value is
// trusted, naming the file and the tag) over many hostile headers written on CT_small's pixels.
struct HostileHeader {
  std::string name;
  int slices;
  std::function<void(DcmDataset&, int)> edit;  // on slice k
  std::string file;                            // the file the message must name
  std::string phrase;                          // what the message must say (tag and value)
};

void PrintTo(const HostileHeader& h, std::ostream* os) { *os << h.name; }

void put(DcmDataset& ds, const DcmTagKey& tag, const char* value) {
  ASSERT_TRUE(ds.putAndInsertString(tag, value).good());
}
void put_us(DcmDataset& ds, const DcmTagKey& tag, Uint16 value) {
  ASSERT_TRUE(ds.putAndInsertUint16(tag, value).good());
}
// The edit on slice `only` alone.
std::function<void(DcmDataset&, int)> on_slice(int only, std::function<void(DcmDataset&)> edit) {
  return [only, edit](DcmDataset& ds, int k) {
    if (k == only) edit(ds);
  };
}
std::function<void(DcmDataset&, int)> on_all(std::function<void(DcmDataset&)> edit) {
  return [edit](DcmDataset& ds, int) { edit(ds); };
}

class ReadImageSeriesHostile : public ::testing::TestWithParam<HostileHeader> {};

TEST_P(ReadImageSeriesHostile, IsInvalidArgumentNamingTheFileAndTheTagInOneLine) {
  const HostileHeader& h = GetParam();
  testing::TempDir dir;
  testing::write_ct_series(dir, h.slices, h.edit);
  auto scan = scan_dicom({dir.path().string()});
  ASSERT_TRUE(scan.ok()) << scan.status().to_string();
  ASSERT_EQ(scan->series.size(), 1u);
  auto r = read_image_series(scan->series[0]);
  ASSERT_FALSE(r.ok()) << "accepted";
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().to_string();
  const std::string& m = r.status().message();
  EXPECT_NE(m.find(dir.file(h.file)), std::string::npos) << m;
  EXPECT_NE(m.find(h.phrase), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
}

INSTANTIATE_TEST_SUITE_P(
    Headers, ReadImageSeriesHostile,
    ::testing::Values(
        HostileHeader{"RowsSmallerThanThePixelData", 2, on_all([](DcmDataset& ds) { put_us(ds, DCM_Rows, 64); }),
                      "ct_0.dcm", "Pixel Data (7FE0,0010) has 32768 bytes but Rows (0028,0010)"},
        HostileHeader{"RowsLargerThanThePixelData", 2, on_all([](DcmDataset& ds) { put_us(ds, DCM_Rows, 256); }),
                      "ct_0.dcm", "needs 65536"},
        HostileHeader{"ColumnsZero", 1, on_all([](DcmDataset& ds) { put_us(ds, DCM_Columns, 0); }), "ct_0.dcm",
                      "Columns (0028,0011) is missing or 0"},
        HostileHeader{"RowsOfOneSliceDiffer", 3, on_slice(1, [](DcmDataset& ds) { put_us(ds, DCM_Rows, 64); }),
                      "ct_1.dcm", "Rows (0028,0010) x Columns (0028,0011) is 64 x 128"},
        HostileHeader{"BitsAllocatedTwelve", 1, on_all([](DcmDataset& ds) { put_us(ds, DCM_BitsAllocated, 12); }),
                      "ct_0.dcm", "Bits Allocated (0028,0100) 12"},
        HostileHeader{"BitsStoredAboveBitsAllocated", 1, on_all([](DcmDataset& ds) { put_us(ds, DCM_BitsStored, 17); }),
                      "ct_0.dcm", "Bits Stored (0028,0101) 17"},
        HostileHeader{"ThreeSamplesPerPixel", 1, on_all([](DcmDataset& ds) { put_us(ds, DCM_SamplesPerPixel, 3); }),
                      "ct_0.dcm", "Samples per Pixel (0028,0002) is 3"},
        HostileHeader{"ZeroFrames", 1, on_all([](DcmDataset& ds) { put(ds, DCM_NumberOfFrames, "0"); }), "ct_0.dcm",
                      "Number of Frames (0028,0008) '0' is not a positive integer"},
        HostileHeader{"TwoFrames", 1, on_all([](DcmDataset& ds) { put(ds, DCM_NumberOfFrames, "2"); }), "ct_0.dcm",
                      "Number of Frames (0028,0008) is 2"},
        HostileHeader{"HugeRescaleSlope", 2, on_slice(1, [](DcmDataset& ds) { put(ds, DCM_RescaleSlope, "1e308"); }),
                      "ct_1.dcm", "Rescale Slope (0028,1053) 1e+308 takes stored value"},
        HostileHeader{"SlopeThatOverflowsTheLargestStoredValue", 1,
                      on_all([](DcmDataset& ds) { put(ds, DCM_RescaleSlope, "1e35"); }), "ct_0.dcm",
                      "Rescale Slope (0028,1053) 1e+35 takes stored value -32768"},
        HostileHeader{"InfiniteRescaleSlope", 1, on_all([](DcmDataset& ds) { put(ds, DCM_RescaleSlope, "inf"); }),
                      "ct_0.dcm", "Rescale Slope (0028,1053) 'inf' is not a finite number"},
        HostileHeader{"NanRescaleSlope", 1, on_all([](DcmDataset& ds) { put(ds, DCM_RescaleSlope, "nan"); }),
                      "ct_0.dcm", "Rescale Slope (0028,1053) 'nan' is not a finite number"},
        HostileHeader{"ZeroRescaleSlope", 1, on_all([](DcmDataset& ds) { put(ds, DCM_RescaleSlope, "0"); }), "ct_0.dcm",
                      "Rescale Slope (0028,1053) 0 would make every voxel the same value"},
        HostileHeader{"RescaleSlopeThatIsNoNumber", 1, on_all([](DcmDataset& ds) { put(ds, DCM_RescaleSlope, "abc"); }),
                      "ct_0.dcm", "Rescale Slope (0028,1053) 'abc' is not a number"},
        HostileHeader{"HugeRescaleIntercept", 1, on_all([](DcmDataset& ds) { put(ds, DCM_RescaleIntercept, "1e39"); }),
                      "ct_0.dcm", "Rescale Intercept (0028,1052) 1e+39 is beyond float's range"},
        HostileHeader{"InfinitePixelSpacing", 1, on_all([](DcmDataset& ds) { put(ds, DCM_PixelSpacing, "inf\\inf"); }),
                      "ct_0.dcm", "Pixel Spacing (0028,0030) inf\\inf must be finite, > 0"},
        HostileHeader{"ZeroPixelSpacing", 2, on_all([](DcmDataset& ds) { put(ds, DCM_PixelSpacing, "0\\0.66"); }),
                      "ct_0.dcm", "Pixel Spacing (0028,0030) 0\\0.66 must be finite, > 0"},
        HostileHeader{"OrientationNotOrthogonal", 2, on_all([](DcmDataset& ds) {
                        put(ds, DCM_ImageOrientationPatient, "1\\0\\0\\0.70710678\\0.70710678\\0");
                      }),
                      "ct_0.dcm", "Image Orientation (Patient) (0020,0037) 1\\0\\0\\0.707107\\0.707107\\0 is not two"},
        HostileHeader{"OrientationNotUnit", 1,
                      on_all([](DcmDataset& ds) { put(ds, DCM_ImageOrientationPatient, "2\\0\\0\\0\\1\\0"); }),
                      "ct_0.dcm", "Image Orientation (Patient) (0020,0037) 2\\0\\0\\0\\1\\0 is not two"},
        HostileHeader{"NanOrientationOnOneSlice", 3,
                      on_slice(2, [](DcmDataset& ds) { put(ds, DCM_ImageOrientationPatient, "1\\0\\0\\0\\nan\\0"); }),
                      "ct_2.dcm", "Image Orientation (Patient) (0020,0037) 1\\0\\0\\0\\nan\\0 is not finite"},
        HostileHeader{
            "NanPositionOnOneSlice", 3,
            on_slice(1, [](DcmDataset& ds) { put(ds, DCM_ImagePositionPatient, "-158.135803\\-179.035797\\nan"); }),
            "ct_1.dcm", "Image Position (Patient) (0020,0032) (-158.136, -179.036, nan) is not a finite"},
        HostileHeader{"InfiniteSpacingBetweenSlicesOfOneSlice", 1,
                      on_all([](DcmDataset& ds) { put(ds, DCM_SpacingBetweenSlices, "inf"); }), "ct_0.dcm",
                      "Spacing Between Slices (0018,0088) inf is not a finite number"}),
    [](const ::testing::TestParamInfo<HostileHeader>& i) { return i.param.name; });

TEST(ReadImageSeries, SyntheticCtSeriesIsReadWhenItsHeadersAreSound) {
  testing::TempDir dir;
  testing::write_ct_series(dir, 3);
  auto scan = scan_dicom({dir.path().string()});
  ASSERT_TRUE(scan.ok());
  auto r = read_image_series(scan->series[0]);
  ASSERT_TRUE(r.ok()) << r.status().to_string();
  EXPECT_EQ(r->image.geometry.dims, (std::array<int64_t, 3>{128, 128, 3}));
  EXPECT_EQ(r->image.geometry.spacing_mm[2], 5);
}

}  // namespace
}  // namespace soiq::dicom
