// Image series -> soiq::Image: the geometry the READMEs state, rescaled values, PET SUV, and the
// series it must refuse.
#include "dicom/read_image_series.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "core/io/read_image.h"
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

}  // namespace
}  // namespace soiq::dicom
