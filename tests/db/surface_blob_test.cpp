#include "db/surface_blob.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/voxelize/memory_estimate.h"
#include "db/deflate.h"
#include "tests/db/surface_blob_testing.h"

namespace soiq::db {
namespace {

using testing::blob_of;
using testing::canonical_bytes;
using testing::header;
using testing::random_mesh;
using testing::same_bits;
using testing::smooth_sphere;
using testing::version2_of;

void expect_data_loss(const std::string& blob, const std::string& phrase);

TEST(SurfaceBlob, RandomMeshesRoundTripBitwise) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const TriangleMesh m = random_mesh(rng, 1 + rng() % 300, rng() % 600);
    auto encoded = encode_surface(m);
    ASSERT_TRUE(encoded.ok()) << encoded.status().to_string();
    auto decoded = decode_surface(encoded->blob);
    ASSERT_TRUE(decoded.ok()) << decoded.status().to_string();
    EXPECT_TRUE(same_bits(m, *decoded)) << "trial " << trial;
  }
}

TEST(SurfaceBlob, EmptyMeshRoundTrips) {
  auto encoded = encode_surface(TriangleMesh{});
  ASSERT_TRUE(encoded.ok());
  auto decoded = decode_surface(encoded->blob);
  ASSERT_TRUE(decoded.ok());
  EXPECT_TRUE(decoded->vertices_mm.empty());
  EXPECT_TRUE(decoded->triangles.empty());
}

TEST(SurfaceBlob, InfoHasCountsAndMinThenMaxBounds) {
  TriangleMesh m;
  m.vertices_mm = {{1, -2, 3}, {-4, 5, 0.5}, {2, 0, -6}};
  m.triangles = {{0, 1, 2}};
  auto encoded = encode_surface(m);
  ASSERT_TRUE(encoded.ok());
  EXPECT_EQ(encoded->info.vertex_count, 3);
  EXPECT_EQ(encoded->info.triangle_count, 1);
  const double expected[6] = {-4, -2, -6, 2, 5, 3};
  for (int i = 0; i < 6; ++i) EXPECT_EQ(encoded->info.bounds_mm[i], expected[i]) << i;
}

TEST(SurfaceBlob, InfoCarriesTheMeasureTheMemoryBudgetNeeds) {
  TriangleMesh m;
  m.vertices_mm = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {0, 0, 10}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  auto encoded = encode_surface(m);
  ASSERT_TRUE(encoded.ok());
  const SurfaceMeasure measure = surface_measure(m);
  ASSERT_GT(measure.area_mm2, 0);
  EXPECT_EQ(encoded->info.area_bound_mm2, measure.area_mm2);
  EXPECT_EQ(encoded->info.perimeter_bound_mm, measure.perimeter_mm);
  // Coordinates whose measure overflows leave it unknown (0, 0) rather than storing infinity.
  m.vertices_mm[1] = {std::numeric_limits<double>::max(), 0, 0};
  m.vertices_mm[2] = {-std::numeric_limits<double>::max(), 1, 0};
  auto huge = encode_surface(m);
  ASSERT_TRUE(huge.ok());
  EXPECT_EQ(huge->info.area_bound_mm2, 0);
  EXPECT_EQ(huge->info.perimeter_bound_mm, 0);
}

TEST(SurfaceBlob, Sha256OfAbcIsTheFips180Vector) {
  EXPECT_EQ(sha256_hex("abc", 3), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("", 0), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
}

TEST(SurfaceBlob, ShaIsOfTheCanonicalBytesAndSeesTheSignOfZero) {
  TriangleMesh a;
  a.vertices_mm = {{0.0, 1, 2}};
  TriangleMesh b = a;
  b.vertices_mm[0][0] = -0.0;
  auto ea = encode_surface(a), eb = encode_surface(b), ea2 = encode_surface(a);
  ASSERT_TRUE(ea.ok() && eb.ok() && ea2.ok());
  EXPECT_NE(ea->info.sha256, eb->info.sha256);
  EXPECT_EQ(ea->info.sha256, ea2->info.sha256);
  EXPECT_EQ(ea->info.sha256, sha256_hex(canonical_bytes(a).data(), canonical_bytes(a).size()));
}

TEST(SurfaceBlob, NonFiniteCoordinateIsInvalidArgument) {
  TriangleMesh m;
  m.vertices_mm = {{0, std::numeric_limits<double>::quiet_NaN(), 0}};
  auto e = encode_surface(m);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(e.status().message().find("non-finite"), std::string::npos);
}

TEST(SurfaceBlob, IndexOutOfRangeIsInvalidArgumentOnEncode) {
  std::mt19937_64 rng(1);
  TriangleMesh m = random_mesh(rng, 3, 1);
  m.triangles[0][1] = 3;
  auto e = encode_surface(m);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.status().code(), StatusCode::kInvalidArgument);
}

void expect_data_loss(const std::string& blob, const std::string& phrase) {
  auto d = decode_surface(blob);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.status().code(), StatusCode::kDataLoss) << d.status().to_string();
  EXPECT_NE(d.status().message().find(phrase), std::string::npos) << d.status().message();
}

TEST(SurfaceBlob, TruncatedBlobIsDataLoss) {
  std::mt19937_64 rng(3);
  auto e = encode_surface(random_mesh(rng, 100, 100));
  ASSERT_TRUE(e.ok());
  for (size_t keep = 0; keep < e->blob.size(); ++keep) {
    auto d = decode_surface(e->blob.substr(0, keep));
    ASSERT_FALSE(d.ok()) << keep;
    EXPECT_EQ(d.status().code(), StatusCode::kDataLoss) << keep << ": " << d.status().to_string();
  }
  expect_data_loss(e->blob + "x", "checksum mismatch");
  expect_data_loss(version2_of(e->blob) + "x", "1 extra bytes");
  expect_data_loss("not a blob at all", "");
}

// A version 2 blob has no checksum of its own: a changed byte is refused when LZ4, the block sizes
// or the indices notice, and otherwise reads as other coordinates, never out of bounds (the
// sanitizer build would say). This is what version 3's checksum is for.
TEST(SurfaceBlob, ChangedBytesOfAVersion2BlobNeverReadOutOfBounds) {
  std::mt19937_64 rng(4);
  auto e = encode_surface(random_mesh(rng, 300, 300));
  ASSERT_TRUE(e.ok());
  const std::string v2 = version2_of(e->blob);
  int refused = 0, read = 0;
  for (size_t at = 8; at < v2.size(); at += 7) {
    std::string blob = v2;
    blob[at] = char(blob[at] ^ 0x5a);
    auto d = decode_surface(blob);
    if (!d.ok()) {
      EXPECT_EQ(d.status().code(), StatusCode::kDataLoss) << d.status().to_string();
      ++refused;
    } else {
      ++read;
      for (const auto& t : d->triangles)
        for (int32_t v : t) EXPECT_TRUE(v >= 0 && size_t(v) < d->vertices_mm.size());
    }
  }
  EXPECT_GT(refused, 0);
  EXPECT_GT(read, 0) << "some changed bytes of a version 2 blob decode to another mesh: the silent case";
}

TEST(SurfaceBlob, AHeaderClaimingMoreThanTheBlobCanHoldIsRefusedBeforeAllocating) {
  std::string blob("SOIQSRF2", 8);
  const uint64_t nv = uint64_t(1) << 40, nt = 1;
  blob.append(reinterpret_cast<const char*>(&nv), 8);
  blob.append(reinterpret_cast<const char*>(&nt), 8);
  expect_data_loss(blob, "more than its 24 bytes can hold");
}

// Counts on both sides of a 512 KiB block (65536 float64, 131072 int32) and of the 16-value groups
// the decoder transposes at once.
TEST(SurfaceBlob, MeshesAroundBlockAndGroupBoundariesRoundTripBitwise) {
  std::mt19937_64 rng(11);
  for (size_t nv :
       {size_t{1}, size_t{15}, size_t{16}, size_t{17}, size_t{65535}, size_t{65536}, size_t{65537}, size_t{140000}}) {
    const size_t nt = nv == 140000 ? 131073 : nv;
    const TriangleMesh m = random_mesh(rng, nv, nt);
    auto e = encode_surface(m);
    ASSERT_TRUE(e.ok()) << e.status().to_string();
    EXPECT_EQ(surface_blob_version(e->blob), 3);
    auto d = decode_surface(e->blob);
    ASSERT_TRUE(d.ok()) << nv << ": " << d.status().to_string();
    EXPECT_TRUE(same_bits(m, *d)) << nv;
  }
}

// A smooth surface (neighbouring vertices close, corners near each other) is what the codec is
// for: it must come out smaller than version 1's zlib of the same mesh.
TEST(SurfaceBlob, ASmoothSurfaceIsSmallerThanItsVersion1Blob) {
  const TriangleMesh m = smooth_sphere(120);
  auto e = encode_surface(m);
  ASSERT_TRUE(e.ok());
  const std::string v1 = blob_of(canonical_bytes(m));
  EXPECT_LT(e->blob.size(), v1.size()) << e->blob.size() << " vs " << v1.size();
  auto d = decode_surface(e->blob);
  ASSERT_TRUE(d.ok());
  EXPECT_TRUE(same_bits(m, *d));
}

// Stores made before version 2 hold zlib blobs: they still read, exactly.
TEST(SurfaceBlob, Version1BlobsStillDecodeExactly) {
  std::mt19937_64 rng(12);
  const TriangleMesh m = random_mesh(rng, 500, 700);
  const std::string v1 = blob_of(canonical_bytes(m));
  EXPECT_TRUE(is_deflated_surface_blob(v1));
  auto d = decode_surface(v1);
  ASSERT_TRUE(d.ok()) << d.status().to_string();
  EXPECT_TRUE(same_bits(m, *d));
}

TEST(SurfaceBlob, WrongMagicOrVersionIsDataLoss) {
  expect_data_loss(blob_of("SOIQIMG!" + header(1, 0, 0).substr(8)), "SOIQSURF");
  expect_data_loss(blob_of(header(2, 0, 0)), "version 2");
}

TEST(SurfaceBlob, CountsThatDisagreeWithThePayloadAreDataLoss) {
  expect_data_loss(blob_of(header(1, 1, 0)), "truncated or padded");
  expect_data_loss(blob_of(header(1, 0, 0) + "x"), "truncated or padded");
  expect_data_loss(blob_of(header(1, uint64_t(1) << 62, uint64_t(1) << 62)), "truncated or padded");
}

TEST(SurfaceBlob, StoredIndexOutOfRangeIsDataLoss) {
  std::string canonical = header(1, 1, 1) + std::string(24, '\0');
  const uint32_t idx[3] = {0, 0, 0xffffffffu};
  canonical.append(reinterpret_cast<const char*>(idx), 12);
  expect_data_loss(blob_of(canonical), "refers to vertex 4294967295");
}

}  // namespace
}  // namespace soiq::db
