// decode_image on uploaded bytes: what read_image gives for every format, and the headers an upload
// may not carry (a separate data file, an offset outside the data, sizes or scaling beyond reason).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "core/io/read_image.h"
#include "core/io/write_image.h"
#include "core/io/zlib_codec.h"
#include "tests/core/io/io_test_files.h"

namespace soiq {
namespace {

using testing_io::data_path;
using testing_io::file_bytes;
using testing_io::write_bytes;

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
