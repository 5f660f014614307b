#include "core/io/read_image.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "core/io/write_image.h"
#include "core/io/zlib_codec.h"
#include "tests/core/io/io_test_files.h"

namespace soiq {
namespace {

using testing_io::file_bytes;

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

TEST(ReadImage, MissingFileIsNotFound) {
  const auto image = read_image(data_path("no_such_image.nrrd"));
  EXPECT_EQ(image.status().code(), StatusCode::kNotFound);
  EXPECT_NE(image.status().message().find("does not exist"), std::string::npos);
}

TEST(ReadImage, UnknownExtensionIsInvalidArgument) {
  const auto image = read_image(write_bytes("image.png", "x"));
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("unknown image extension '.png'"), std::string::npos);
}

TEST(ReadImage, EmptyFileIsInvalidArgument) {
  for (const char* name : {"empty.nii.gz", "empty.nrrd", "empty.mha"}) {
    const auto image = read_image(write_bytes(name, ""));
    EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument) << name;
    EXPECT_NE(image.status().message().find("is empty"), std::string::npos) << image.status().message();
  }
}

TEST(ReadImage, TruncatedNiftiGzIsInvalidArgument) {
  // Cut a real compressed image in half: the gzip stream ends inside the voxel data.
  std::ifstream in(data_path("sts/STS_002/PET_image.nii.gz"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string path = write_bytes("truncated.nii.gz", bytes.substr(0, bytes.size() / 2));
  const auto image = read_image(path);
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("truncated"), std::string::npos) << image.status().message();
  EXPECT_NE(image.status().message().find(path), std::string::npos);
}

TEST(ReadImage, TruncatedUncompressedNiftiIsInvalidArgument) {
  Mask mask;
  mask.geometry.dims = {10, 10, 10};
  mask.voxels.assign(1000, 1);
  const std::string path = testing_io::scratch_path("cut.nii");
  ASSERT_TRUE(write_mask(mask, path).ok());
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write_bytes("cut.nii", bytes.substr(0, bytes.size() - 10));
  const auto image = read_image(path);
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("truncated"), std::string::npos) << image.status().message();
}

TEST(ReadImage, NrrdWithoutSizesIsInvalidArgument) {
  const auto image =
      read_image(write_bytes("nosizes.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nencoding: raw\n\n\x01\x02"));
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("no 'sizes' field"), std::string::npos) << image.status().message();
}

TEST(ReadImage, NrrdWithMalformedHeaderLineIsInvalidArgument) {
  const auto image = read_image(write_bytes("badline.nrrd", "NRRD0004\nthis is not a field\n\n"));
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("malformed line"), std::string::npos) << image.status().message();
}

TEST(ReadImage, NrrdWithoutMagicIsInvalidArgument) {
  const auto image = read_image(write_bytes("nomagic.nrrd", "hello\n"));
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("not a NRRD file"), std::string::npos) << image.status().message();
}

TEST(ReadImage, Nrrd4dIsInvalidArgument) {
  const auto image = read_image(
      write_bytes("four.nrrd", "NRRD0004\ntype: uint8\ndimension: 4\nsizes: 1 1 1 1\nencoding: raw\n\n\x01"));
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("3D images only"), std::string::npos) << image.status().message();
}

TEST(ReadImage, TruncatedRawNrrdIsInvalidArgument) {
  const auto image = read_image(write_bytes(
      "short.nrrd", "NRRD0004\ntype: short\ndimension: 3\nsizes: 2 2 2\nendian: little\nencoding: raw\n\n\x01\x02"));
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("truncated"), std::string::npos) << image.status().message();
}

TEST(ReadImage, CorruptGzipNrrdIsInvalidArgument) {
  const auto image = read_image(write_bytes(
      "corrupt.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: gzip\n\nnot gzip at all"));
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("corrupt"), std::string::npos) << image.status().message();
}

TEST(ReadImage, ShearedNrrdIsInvalidArgument) {
  const auto image = read_image(write_bytes("shear.nrrd",
                                            "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 1 1 1\n"
                                            "space directions: (1,0,0) (1,1,0) (0,0,1)\nencoding: ascii\n\n1\n"));
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("sheared or non-orthogonal"), std::string::npos) << image.status().message();
}

TEST(ReadImage, TruncatedMetaImageIsInvalidArgument) {
  const auto image = read_image(write_bytes("short.mha",
                                            "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\n"
                                            "ElementType = MET_FLOAT\nElementDataFile = LOCAL\n1234"));
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("truncated"), std::string::npos) << image.status().message();
}

TEST(ReadImage, HugeNrrdGridIsResourceExhausted) {
  const auto image = read_image(
      write_bytes("huge.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 100000 100000 100000\nencoding: raw\n\n"));
  EXPECT_EQ(image.status().code(), StatusCode::kResourceExhausted);
}

// An uncompressed single-file NIfTI-1 of a 10x10x10 uint8 mask, written by our writer (libnifti).
std::string small_nifti_bytes() {
  Mask mask;
  mask.geometry.dims = {10, 10, 10};
  mask.voxels.assign(1000, 0);
  for (size_t n = 0; n < mask.voxels.size(); n += 3) mask.voxels[n] = 1;
  const std::string path = testing_io::scratch_path("small.nii");
  EXPECT_TRUE(write_mask(mask, path).ok());
  return file_bytes(path);
}

TEST(DecodeImage, GivesWhatReadImageGivesForEveryFormat) {
  for (const char* relative :
       {"pyradiomics/brain1_label.nrrd", "sts/STS_002/PET_image.nii.gz", "ibsi_digital_phantom/mask.nii.gz"}) {
    const std::string path = data_path(relative);
    const auto from_file = read_image(path);
    ASSERT_TRUE(from_file.ok()) << from_file.status().to_string();
    const std::string format = std::string(relative).ends_with(".nii.gz") ? "nii.gz" : "nrrd";
    const auto from_bytes = decode_image(file_bytes(path), format, "upload");
    ASSERT_TRUE(from_bytes.ok()) << from_bytes.status().to_string();
    EXPECT_EQ(from_bytes->geometry.dims, from_file->geometry.dims) << relative;
    EXPECT_EQ(from_bytes->geometry.origin_mm, from_file->geometry.origin_mm) << relative;
    EXPECT_TRUE(from_bytes->voxels == from_file->voxels) << relative;
  }
  // MetaImage and uncompressed NIfTI, through our writers.
  const auto phantom = read_image(data_path("ibsi_digital_phantom/phantom.nii.gz"));
  ASSERT_TRUE(phantom.ok());
  for (const char* name : {"phantom.mha", "phantom.nii"}) {
    const std::string path = testing_io::scratch_path(name);
    ASSERT_TRUE(write_image(*phantom, path).ok());
    const auto back = decode_image(file_bytes(path), std::string(name).substr(8), name);
    ASSERT_TRUE(back.ok()) << back.status().to_string();
    EXPECT_TRUE(back->voxels == phantom->voxels) << name;
  }
}

// The attack: an uploaded header names a server file as its voxel data, and the file's bytes come
// back as voxel values. Read locally, a header may name its neighbour; uploaded, it may not.
TEST(DecodeImage, NrrdNamingADataFileIsRefused) {
  const std::string secret = write_bytes("secret.raw", std::string(8, 'S'));
  for (const std::string& field :
       std::vector<std::string>{"data file: " + secret, "datafile: secret.raw", "data file: LIST"}) {
    const std::string header = "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n" + field + "\n\n";
    const auto image = decode_image(header, "nrrd", "evil.nrrd");
    EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument) << field;
    EXPECT_NE(image.status().message().find("names a separate data file"), std::string::npos)
        << image.status().message();
    EXPECT_EQ(image.status().message().find('\n'), std::string::npos);
  }
  // The same header as a local file still reads its neighbour (the user's own files).
  const std::string local = write_bytes(
      "local.nhdr", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\nencoding: raw\ndata file: secret.raw\n\n");
  const auto image = read_image(local);
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  EXPECT_EQ(image->voxels[0], float('S'));
}

TEST(DecodeImage, MetaImageNamingADataFileIsRefused) {
  const std::string secret = write_bytes("secret2.raw", std::string(8, 'S'));
  for (const std::string& name : std::vector<std::string>{secret, "secret2.raw", "LIST"}) {
    const std::string header =
        "ObjectType = Image\nNDims = 3\nDimSize = 2 2 2\nElementType = MET_UCHAR\nElementDataFile = " + name + "\n";
    const auto image = decode_image(header, "mha", "evil.mha");
    EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument) << name;
    EXPECT_NE(image.status().message().find("names a separate data file"), std::string::npos)
        << image.status().message();
  }
}

TEST(DecodeImage, TwoFileNiftiHeaderIsRefused) {
  std::string bytes = small_nifti_bytes();
  std::memcpy(bytes.data() + 344, "ni1\0", 4);  // magic: the header of a .hdr/.img pair
  const auto image = decode_image(bytes, "nii", "pair.nii");
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find(".hdr/.img"), std::string::npos) << image.status().message();
}

TEST(DecodeImage, NiftiVoxOffsetPastTheDataOrInsideTheHeaderIsRefused) {
  const std::string good = small_nifti_bytes();
  for (const float offset : {352.0f + 64, 1e9f, 100.0f, -5.0f, std::numeric_limits<float>::quiet_NaN(), 3e38f}) {
    std::string bytes = good;
    std::memcpy(bytes.data() + 108, &offset, 4);  // vox_offset
    for (const bool gz : {false, true}) {
      std::string upload = bytes;
      if (gz) {
        auto deflated = deflate_bytes(bytes, ZlibFormat::kGzip);
        ASSERT_TRUE(deflated.ok());
        upload = *deflated;
      }
      const auto image = decode_image(upload, gz ? "nii.gz" : "nii", "offset.nii");
      EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument) << offset << " gz " << gz;
      EXPECT_NE(image.status().message().find("vox_offset"), std::string::npos) << image.status().message();
    }
  }
}

TEST(DecodeImage, NiftiWithAbsurdDimsInATinyGzipFailsWithoutAllocating) {
  std::string bytes = small_nifti_bytes();
  const int16_t dims[4] = {3, 1000, 1000, 900};  // 9e8 voxels of uint8, announced by a ~1 KB file
  std::memcpy(bytes.data() + 40, dims, sizeof dims);
  auto deflated = deflate_bytes(bytes, ZlibFormat::kGzip);
  ASSERT_TRUE(deflated.ok());
  const auto image = decode_image(*deflated, "nii.gz", "bomb.nii.gz");
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("truncated"), std::string::npos) << image.status().message();
  int16_t bad_rank = 9;
  std::memcpy(bytes.data() + 40, &bad_rank, 2);
  EXPECT_EQ(decode_image(bytes, "nii", "rank.nii").status().code(), StatusCode::kInvalidArgument);
}

// Found by fuzz_nifti: a 0 in dim[3] of a 2D header made an empty grid. Sizes beyond dim[0] count as 1.
TEST(DecodeImage, NiftiSizesBeyondDim0CountAsOne) {
  std::string bytes = small_nifti_bytes();
  const int16_t dims[4] = {2, 10, 10, 0};
  std::memcpy(bytes.data() + 40, dims, sizeof dims);
  const auto image = decode_image(bytes, "nii", "flat.nii");
  ASSERT_TRUE(image.ok()) << image.status().to_string();
  EXPECT_EQ(image->geometry.dims, (std::array<int64_t, 3>{10, 10, 1}));
  EXPECT_EQ(image->voxels.size(), 100u);
}

TEST(DecodeImage, NiftiScalingBeyondFloatIsRefused) {
  std::string bytes = small_nifti_bytes();
  const float slope = 3e38f, inter = 1e38f;    // a voxel of 1 becomes 4e38, beyond float
  std::memcpy(bytes.data() + 112, &slope, 4);  // scl_slope
  std::memcpy(bytes.data() + 116, &inter, 4);  // scl_inter
  const auto image = decode_image(bytes, "nii", "scale.nii");
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("scl_slope"), std::string::npos) << image.status().message();
}

TEST(DecodeImage, NotNiftiAtAllIsInvalidArgument) {
  const auto image = decode_image(std::string(400, 'x'), "nii", "junk.nii");
  EXPECT_EQ(image.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(image.status().message().find("not a NIfTI file"), std::string::npos) << image.status().message();
}

}  // namespace
}  // namespace soiq
