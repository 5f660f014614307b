#include "db/image_blob.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "db/deflate.h"

namespace soiq::db {
namespace {

Image random_image(uint64_t seed) {
  std::mt19937_64 rng(seed);
  Image img;
  img.geometry.dims = {int64_t(1 + rng() % 7), int64_t(1 + rng() % 5), int64_t(1 + rng() % 4)};
  img.geometry.spacing_mm = {0.7, 1.1, 2.5};
  img.geometry.origin_mm = {-120.25, 33.0, 1e-3};
  const float specials[] = {0.0f,
                            -0.0f,
                            std::numeric_limits<float>::denorm_min(),
                            std::numeric_limits<float>::max(),
                            -3.4e38f,
                            std::numeric_limits<float>::quiet_NaN()};
  std::uniform_real_distribution<float> value(-1000, 3000);
  img.voxels.resize(size_t(img.geometry.voxel_count()));
  for (size_t i = 0; i < img.voxels.size(); ++i) img.voxels[i] = i % 3 == 0 ? specials[rng() % 6] : value(rng);
  return img;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

TEST(ImageBlob, RandomImagesRoundTripBitwise) {
  for (uint64_t seed = 0; seed < 30; ++seed) {
    const Image img = random_image(seed);
    auto e = encode_image(img);
    ASSERT_TRUE(e.ok()) << e.status().to_string();
    auto d = decode_image(e->blob, img.geometry);
    ASSERT_TRUE(d.ok()) << d.status().to_string();
    EXPECT_TRUE(same_bits(img.voxels, d->voxels)) << "seed " << seed;
    EXPECT_EQ(d->geometry, img.geometry);
  }
}

TEST(ImageBlob, ShaCoversTheGeometryAsWellAsTheVoxels) {
  const Image a = random_image(1);
  Image b = a;
  b.geometry.origin_mm[2] = std::nextafter(b.geometry.origin_mm[2], 1.0);  // one ulp away
  Image c = a;
  c.voxels[1] = std::nextafter(c.voxels[1], 1e9f);
  const auto ea = encode_image(a), eb = encode_image(b), ec = encode_image(c), ea2 = encode_image(a);
  EXPECT_EQ(ea->sha256, ea2->sha256);
  EXPECT_NE(ea->sha256, eb->sha256);
  EXPECT_NE(ea->sha256, ec->sha256);
  EXPECT_EQ(ea->blob, eb->blob);  // same voxels, so the same blob: the geometry is not in it
  EXPECT_EQ(ea->sha256.size(), 64u);
}

TEST(ImageBlob, VoxelCountThatDisagreesWithTheGridIsInvalidArgument) {
  Image img = random_image(2);
  img.voxels.pop_back();
  auto e = encode_image(img);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.status().code(), StatusCode::kInvalidArgument);
}

TEST(ImageBlob, BlobOfAnotherGridSizeIsDataLoss) {
  const Image img = random_image(3);
  auto e = encode_image(img);
  ImageGeometry bigger = img.geometry;
  bigger.dims[0] += 1;
  ImageGeometry smaller = img.geometry;
  smaller.dims[2] = 0;
  for (const ImageGeometry& g : {bigger, smaller}) {
    auto d = decode_image(e->blob, g);
    ASSERT_FALSE(d.ok());
    EXPECT_EQ(d.status().code(), StatusCode::kDataLoss) << d.status().to_string();
  }
}

TEST(ImageBlob, TruncatedOrCorruptBlobIsDataLoss) {
  const Image img = random_image(4);
  auto e = encode_image(img);
  std::string flipped = e->blob;
  flipped[flipped.size() / 2] = char(flipped[flipped.size() / 2] ^ 0x11);
  for (const std::string& blob : {e->blob.substr(0, e->blob.size() - 3), flipped, std::string()}) {
    auto d = decode_image(blob, img.geometry);
    ASSERT_FALSE(d.ok());
    EXPECT_EQ(d.status().code(), StatusCode::kDataLoss) << d.status().to_string();
  }
}

// A blob stored before the delta-planes codec (version 1: the raw bytes deflated) still decodes.
TEST(ImageBlob, AVersion1BlobStillDecodes) {
  const Image img = random_image(5);
  auto v1 = deflate_bytes(img.voxels.data(), img.voxels.size() * sizeof(float));
  ASSERT_TRUE(v1.ok());
  EXPECT_TRUE(is_deflated_image_blob(*v1));
  EXPECT_FALSE(is_deflated_image_blob(encode_image(img)->blob));
  auto d = decode_image(*v1, img.geometry);
  ASSERT_TRUE(d.ok()) << d.status().to_string();
  EXPECT_TRUE(same_bits(d->voxels, img.voxels));
}

// A CT-like image (smooth integers, as rescaled 12-bit pixels are): lossless, and smaller than raw.
TEST(ImageBlob, ASmoothImageCompressesAndRoundTrips) {
  Image img;
  img.geometry.dims = {64, 64, 16};
  for (int64_t k = 0; k < 16; ++k)
    for (int64_t j = 0; j < 64; ++j)
      for (int64_t i = 0; i < 64; ++i)
        img.voxels.push_back(float(std::lround(200 * std::sin(0.1 * double(i)) * std::cos(0.07 * double(j)) + k)));
  auto e = encode_image(img);
  ASSERT_TRUE(e.ok());
  EXPECT_LT(e->blob.size(), img.voxels.size() * sizeof(float) / 2);
  auto d = decode_image(e->blob, img.geometry);
  ASSERT_TRUE(d.ok()) << d.status().to_string();
  EXPECT_TRUE(same_bits(d->voxels, img.voxels));
}

}  // namespace
}  // namespace soiq::db
