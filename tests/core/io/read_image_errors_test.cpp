// read_image on files it refuses: each error path with its code and a key phrase of its message.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>

#include "core/io/read_image.h"
#include "core/io/write_image.h"
#include "tests/core/io/io_test_files.h"

namespace soiq {
namespace {

using testing_io::data_path;
using testing_io::write_bytes;

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

}  // namespace
}  // namespace soiq
