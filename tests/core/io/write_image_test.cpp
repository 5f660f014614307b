#include "core/io/write_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/io/read_image.h"
#include "tests/core/io/io_test_files.h"

namespace soiq {
namespace {

using testing_io::scratch_path;

// An oblique grid: a rotation about a skew axis, with non-round spacing and origin.
ImageGeometry oblique_geometry(bool mirrored) {
  ImageGeometry g;
  g.dims = {7, 5, 3};
  g.spacing_mm = {0.7, 1.3, 2.9};
  g.origin_mm = {-101.25, 37.125, 12.3456789};
  const double a = 0.3, b = -0.7;  // Rz(a) * Rx(b)
  const Mat3 rz{{{std::cos(a), -std::sin(a), 0}, {std::sin(a), std::cos(a), 0}, {0, 0, 1}}};
  const Mat3 rx{{{1, 0, 0}, {0, std::cos(b), -std::sin(b)}, {0, std::sin(b), std::cos(b)}}};
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      g.direction[r][c] = 0;
      for (int k = 0; k < 3; ++k) g.direction[r][c] += rz[r][k] * rx[k][c];
    }
  }
  if (mirrored) {
    for (int r = 0; r < 3; ++r) g.direction[r][2] = -g.direction[r][2];  // determinant -1
  }
  return g;
}

void expect_geometry_near(const ImageGeometry& got, const ImageGeometry& want, double tolerance) {
  EXPECT_EQ(got.dims, want.dims);
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(got.origin_mm[a], want.origin_mm[a], tolerance);
    EXPECT_NEAR(got.spacing_mm[a], want.spacing_mm[a], tolerance);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got.direction[a][c], want.direction[a][c], tolerance);
  }
}

// NRRD and MetaImage print 17 significant digits: geometry comes back exact to rounding.
// NIfTI-1 stores its affine in float32: ~1e-7 relative, i.e. < 1e-4 mm on these coordinates.
double tolerance_for(const std::string& ext) { return ext == ".nrrd" || ext == ".mha" ? 1e-9 : 1e-4; }

class WriteImageRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(WriteImageRoundTrip, MaskComesBackWithSameGeometryAndVoxels) {
  for (const bool mirrored : {false, true}) {
    Mask mask;
    mask.geometry = oblique_geometry(mirrored);
    for (int64_t n = 0; n < mask.geometry.voxel_count(); ++n) mask.voxels.push_back(uint8_t(n % 3 == 0));
    const std::string path = scratch_path(std::string("mask") + (mirrored ? "_m" : "") + GetParam());
    ASSERT_TRUE(write_mask(mask, path).ok());
    const auto back = read_image(path);
    ASSERT_TRUE(back.ok()) << back.status().to_string();
    expect_geometry_near(back->geometry, mask.geometry, tolerance_for(GetParam()));
    EXPECT_EQ(mask_from_image(*back).voxels, mask.voxels);
  }
}

TEST_P(WriteImageRoundTrip, FloatImageComesBackWithSameVoxels) {
  Image image;
  image.geometry = oblique_geometry(false);
  for (int64_t n = 0; n < image.geometry.voxel_count(); ++n) image.voxels.push_back(float(n) * 0.37f - 11.1f);
  const std::string path = scratch_path("image" + GetParam());
  ASSERT_TRUE(write_image(image, path).ok());
  const auto back = read_image(path);
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  expect_geometry_near(back->geometry, image.geometry, tolerance_for(GetParam()));
  EXPECT_EQ(back->voxels, image.voxels);
}

TEST_P(WriteImageRoundTrip, Brain1LabelGeometryComesBackExactly) {
  const auto brain = read_image(testing_io::data_path("pyradiomics/brain1_label.nrrd"));
  ASSERT_TRUE(brain.ok()) << brain.status().to_string();
  const Mask mask = mask_from_image(*brain, 1);
  const std::string path = scratch_path("brain1" + GetParam());
  ASSERT_TRUE(write_mask(mask, path).ok());
  const auto back = read_image(path);
  ASSERT_TRUE(back.ok()) << back.status().to_string();
  expect_geometry_near(back->geometry, mask.geometry, tolerance_for(GetParam()));
  EXPECT_EQ(mask_from_image(*back).voxels, mask.voxels);
}

INSTANTIATE_TEST_SUITE_P(Formats, WriteImageRoundTrip, ::testing::Values(".nrrd", ".mha", ".nii", ".nii.gz"),
                         [](const auto& info) {
                           std::string name = info.param.substr(1);
                           for (char& c : name) c = c == '.' ? '_' : c;
                           return name;
                         });

TEST(WriteImage, UnknownExtensionIsInvalidArgument) {
  Mask mask;
  mask.geometry.dims = {1, 1, 1};
  mask.voxels = {1};
  const Status s = write_mask(mask, scratch_path("mask.tiff"));
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("unknown image extension"), std::string::npos) << s.message();
}

TEST(WriteImage, MissingDirectoryIsNotFound) {
  Mask mask;
  mask.geometry.dims = {1, 1, 1};
  mask.voxels = {1};
  for (const char* ext : {".nrrd", ".mha", ".nii.gz"}) {
    const Status s = write_mask(mask, scratch_path(std::string("no/such/dir/mask") + ext));
    EXPECT_EQ(s.code(), StatusCode::kNotFound) << s.to_string();
    EXPECT_NE(s.message().find("directory does not exist"), std::string::npos) << s.message();
  }
}

TEST(WriteImage, WrongVoxelCountIsInvalidArgument) {
  Mask mask;
  mask.geometry.dims = {2, 2, 2};
  mask.voxels = {1};
  const Status s = write_mask(mask, scratch_path("wrong.nrrd"));
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq
