// Surface blobs of version 3 (db/surface_blob.h): a CRC-32 over every stored byte, so that every
// flipped bit, in the header, in each block of each plane stream or in the checksum itself, is
// DATA_LOSS and never another mesh; version 2 blobs of the same mesh still decode; the sha256
// stays that of the canonical bytes.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "db/delta_planes.h"
#include "db/surface_blob.h"
#include "tests/db/surface_blob_testing.h"

namespace soiq::db {
namespace {

using testing::blob_of;
using testing::canonical_bytes;
using testing::random_mesh;
using testing::same_bits;
using testing::smooth_sphere;
using testing::version2_of;

TEST(SurfaceBlobChecksum, NewBlobsAreVersion3AndTheVersion2BlobOfTheSameMeshStillDecodes) {
  std::mt19937_64 rng(21);
  const TriangleMesh m = random_mesh(rng, 200, 300);
  auto e = encode_surface(m);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->blob.substr(0, 8), "SOIQSRC3");
  EXPECT_EQ(surface_blob_version(e->blob), 3);
  const std::string v2 = version2_of(e->blob);
  EXPECT_EQ(surface_blob_version(v2), 2);
  auto d = decode_surface(v2);
  ASSERT_TRUE(d.ok()) << d.status().to_string();
  EXPECT_TRUE(same_bits(m, *d));
  EXPECT_EQ(surface_blob_version(blob_of(canonical_bytes(m))), 1);
}

TEST(SurfaceBlobChecksum, TheShaOfAMeshIsTheOneItsEncodingGivesWithoutEncodingIt) {
  std::mt19937_64 rng(22);
  const TriangleMesh m = random_mesh(rng, 50, 80);
  auto e = encode_surface(m);
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(surface_sha256(m), e->info.sha256);
  EXPECT_EQ(surface_sha256(m), sha256_hex(canonical_bytes(m).data(), canonical_bytes(m).size()));
}

// Decodes `blob` with bit `bit` of byte `at` flipped (and flips it back): DATA_LOSS, never a mesh,
// and past the magic, the checksum is what says so.
void expect_flip_refused(std::string& blob, size_t at, int bit) {
  blob[at] = char(blob[at] ^ (1 << bit));
  auto d = decode_surface(blob);
  blob[at] = char(blob[at] ^ (1 << bit));
  ASSERT_FALSE(d.ok()) << "byte " << at << " bit " << bit << " decoded to a mesh";
  EXPECT_EQ(d.status().code(), StatusCode::kDataLoss) << d.status().to_string();
  if (at >= 8) {
    EXPECT_TRUE(d.status().message().find("checksum mismatch") != std::string::npos) << d.status().message();
  }
}

TEST(SurfaceBlobChecksum, EveryFlippedBitOfASmallVersion3BlobIsDataLoss) {
  std::mt19937_64 rng(23);
  auto e = encode_surface(random_mesh(rng, 12, 20));
  ASSERT_TRUE(e.ok());
  std::string blob = e->blob;
  for (size_t at = 0; at < blob.size(); ++at)
    for (int bit = 0; bit < 8; ++bit) expect_flip_refused(blob, at, bit);
  EXPECT_TRUE(decode_surface(blob).ok());  // every bit flipped back
}

// Meshes of more than one 512 KiB block per plane (65536 float64, 131072 int32), smooth and random
// (LZ4 blocks), and a small random one whose blocks LZ4 cannot shrink, stored as they are: the case
// where a flipped bit in a version 2 blob reads as another coordinate. Every bit of the header
// (magic, checksum, counts), of each block's size word, and of the first, middle and last byte of
// each block of each plane stream is flipped in turn, and the last byte of the blob.
TEST(SurfaceBlobChecksum, FlippedBitsInEachPartOfVersion3BlobsAreDataLoss) {
  std::mt19937_64 rng(24);
  int lz4_blocks = 0, stored_blocks = 0, planes_of_several_blocks = 0;
  for (const TriangleMesh& m : {smooth_sphere(300), random_mesh(rng, 70000, 140000), random_mesh(rng, 5, 3)}) {
    auto e = encode_surface(m);
    ASSERT_TRUE(e.ok());
    std::string blob = e->blob;
    for (size_t at = 0; at < 28; ++at)
      for (int bit = 0; bit < 8; ++bit) expect_flip_refused(blob, at, bit);
    size_t at = 28;
    for (int plane = 0; plane < 6; ++plane) {
      const size_t count = plane < 3 ? m.vertices_mm.size() : m.triangles.size();
      const size_t per_block = kBlockBytes / (plane < 3 ? 8 : 4);
      planes_of_several_blocks += count > per_block;
      for (size_t from = 0; from < count; from += per_block) {
        uint32_t header = 0;
        ASSERT_LE(at + 4, blob.size());
        std::memcpy(&header, blob.data() + at, 4);
        const size_t size = header & 0x7fffffffu;
        ++(header >> 31 ? stored_blocks : lz4_blocks);
        for (size_t b = at; b < at + 4; ++b)
          for (int bit = 0; bit < 8; ++bit) expect_flip_refused(blob, b, bit);
        for (const size_t b : {at + 4, at + 4 + size / 2, at + 3 + size})
          for (int bit = 0; bit < 8; ++bit) expect_flip_refused(blob, b, bit);
        at += 4 + size;
      }
    }
    EXPECT_EQ(at, blob.size()) << "the walk over the blocks must end where the blob does";
    for (int bit = 0; bit < 8; ++bit) expect_flip_refused(blob, blob.size() - 1, bit);
    auto d = decode_surface(blob);
    ASSERT_TRUE(d.ok()) << d.status().to_string();
    EXPECT_TRUE(same_bits(m, *d));
  }
  EXPECT_EQ(planes_of_several_blocks, 12);  // every plane of both large meshes
  EXPECT_GT(lz4_blocks, 0);
  EXPECT_GT(stored_blocks, 0);
}

}  // namespace
}  // namespace soiq::db
