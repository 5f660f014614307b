// read_image on the files of each format: NRRD, NIfTI and MetaImage geometry and voxels as their
// headers give them, and mask_from_image.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/io/read_image.h"
#include "tests/core/io/io_test_files.h"

namespace soiq {
namespace {

using testing_io::data_path;
using testing_io::write_bytes;

TEST(ReadImage, Brain1LabelNrrdGeometryMatchesItsHeader) {
  const auto image = read_image(data_path("pyradiomics/brain1_label.nrrd"));
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  const ImageGeometry& g = image->geometry;
  EXPECT_EQ(g.dims, (std::array<int64_t, 3>{256, 256, 25}));
  // The header's numbers, parsed exactly (a vector's norm of a single nonzero component is exact).
  EXPECT_EQ(g.spacing_mm, (Vec3{0.78124999999999989, 0.78124999999999989, 6.4999999999999982}));
  EXPECT_EQ(g.origin_mm, (Vec3{-99.609374999999986, 99.609374999999986, -77.999999999999957}));
  EXPECT_EQ(g.direction, (Mat3{{{1, 0, 0}, {0, -1, 0}, {0, 0, 1}}}));
  EXPECT_EQ(image->voxels.size(), size_t(256 * 256 * 25));
}

TEST(ReadImage, Brain1LabelHas4137VoxelsOfLabel1) {
  const auto image = read_image(data_path("pyradiomics/brain1_label.nrrd"));
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  const Mask mask = mask_from_image(*image, 1);
  EXPECT_EQ(std::count(mask.voxels.begin(), mask.voxels.end(), 1), 4137);
}

TEST(ReadImage, StsNiftiMasksAreAxialWithIdentityDirection) {
  for (const char* patient : {"STS_002", "STS_008", "STS_012", "STS_025"}) {
    for (const char* modality : {"CT", "MR_T1", "PET"}) {
      const std::string path = data_path(std::string("sts/") + patient + "/" + modality + "_mask.nii.gz");
      const auto image = read_image(path);
      ASSERT_TRUE(image.ok()) << image.status().to_string();
      const ImageGeometry& g = image->geometry;
      SCOPED_TRACE(path + ": " + describe(g));
      for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(g.direction[r][c], r == c ? 1.0 : 0.0, 1e-6);  // float header
      }
      for (int a = 0; a < 3; ++a) {
        EXPECT_GT(g.dims[a], 1);
        EXPECT_GT(g.spacing_mm[a], 0.1);
        EXPECT_LT(g.spacing_mm[a], 10.0);
      }
      const Mask mask = mask_from_image(*image);
      EXPECT_GT(std::count(mask.voxels.begin(), mask.voxels.end(), 1), 0);
    }
  }
}

TEST(ReadImage, IbsiDigitalPhantomIs5x4x4With2mmVoxels) {
  const auto image = read_image(data_path("ibsi_digital_phantom/phantom.nii.gz"));
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  EXPECT_EQ(image->geometry.dims, (std::array<int64_t, 3>{5, 4, 4}));
  EXPECT_EQ(image->geometry.spacing_mm, (Vec3{2, 2, 2}));
  const auto mask = read_image(data_path("ibsi_digital_phantom/mask.nii.gz"));
  ASSERT_TRUE(mask.ok()) << mask.status().to_string();
  EXPECT_EQ(mask->geometry, image->geometry);
}

TEST(ReadImage, PetImageHasPositiveSuvValues) {
  const auto image = read_image(data_path("sts/STS_002/PET_image.nii.gz"));
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  EXPECT_GT(*std::max_element(image->voxels.begin(), image->voxels.end()), 1.0f);
}

TEST(ReadImage, NrrdInRasSpaceIsConvertedToLps) {
  const std::string path = write_bytes("ras.nrrd",
                                       "NRRD0004\ntype: uint8\ndimension: 3\nspace: right-anterior-superior\n"
                                       "sizes: 2 1 1\nspace directions: (2,0,0) (0,3,0) (0,0,4)\n"
                                       "encoding: ascii\nspace origin: (10,20,30)\n\n0 7\n");
  const auto image = read_image(path);
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  EXPECT_EQ(image->geometry.origin_mm, (Vec3{-10, -20, 30}));
  EXPECT_EQ(image->geometry.spacing_mm, (Vec3{2, 3, 4}));
  EXPECT_EQ(image->geometry.direction, (Mat3{{{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}}}));
  EXPECT_EQ(image->voxels, (std::vector<float>{0, 7}));
}

TEST(ReadImage, MetaImageTransformMatrixListsTheDirectionColumns) {
  // Axis i points along +y, axis j along -x, axis k along +z (ITK: TransformMatrix[i*3+j] = D(:,i)[j]).
  std::string text =
      "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = True\n"
      "TransformMatrix = 0 1 0 -1 0 0 0 0 1\nOffset = 1 2 3\nElementSpacing = 0.5 0.25 2\n"
      "DimSize = 2 1 1\nElementType = MET_SHORT\nElementDataFile = LOCAL\n";
  text += std::string("\x01\x02\xff\xfe", 4);  // big-endian 258, -2
  const auto image = read_image(write_bytes("rotated.mha", text));
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  EXPECT_EQ(image->geometry.direction, (Mat3{{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}}}));
  EXPECT_EQ(image->geometry.spacing_mm, (Vec3{0.5, 0.25, 2}));
  EXPECT_EQ(image->geometry.origin_mm, (Vec3{1, 2, 3}));
  EXPECT_EQ(image->voxels, (std::vector<float>{258, -2}));
}

TEST(ReadImage, MaskFromImageWithoutLabelKeepsNonzeroVoxels) {
  Image image;
  image.geometry.dims = {4, 1, 1};
  image.voxels = {0, 1, 2, -3};
  EXPECT_EQ(mask_from_image(image).voxels, (std::vector<uint8_t>{0, 1, 1, 1}));
  EXPECT_EQ(mask_from_image(image, 2).voxels, (std::vector<uint8_t>{0, 0, 1, 0}));
}

}  // namespace
}  // namespace soiq
