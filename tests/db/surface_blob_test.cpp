#include "db/surface_blob.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>

#include "db/deflate.h"

namespace soiq::db {
namespace {

// Bitwise equality: == on doubles would accept -0.0 for +0.0.
bool same_bits(const TriangleMesh& a, const TriangleMesh& b) {
  return a.vertices_mm.size() == b.vertices_mm.size() && a.triangles == b.triangles &&
         (a.vertices_mm.empty() ||
          std::memcmp(a.vertices_mm.data(), b.vertices_mm.data(), a.vertices_mm.size() * sizeof(Vec3)) == 0);
}

TriangleMesh random_mesh(std::mt19937_64& rng, size_t nv, size_t nt) {
  // Ordinary values mixed with the ones a lossy encoding would get wrong.
  const double specials[] = {0.0,
                             -0.0,
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::min() / 3,
                             std::numeric_limits<double>::max(),
                             -std::numeric_limits<double>::max(),
                             1e300,
                             0.1,
                             1.0 / 3.0};
  std::uniform_real_distribution<double> coord(-500, 500);
  std::uniform_int_distribution<int> pick(0, 19);
  TriangleMesh m;
  for (size_t i = 0; i < nv; ++i) {
    Vec3 v;
    for (double& x : v) {
      const int k = pick(rng);
      x = k < 10 ? specials[k] : coord(rng);
    }
    m.vertices_mm.push_back(v);
  }
  std::uniform_int_distribution<int32_t> index(0, int32_t(nv) - 1);
  for (size_t t = 0; t < nt; ++t) m.triangles.push_back({index(rng), index(rng), index(rng)});
  return m;
}

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
  auto canonical = inflate_bytes(ea->blob, 1 << 20);
  ASSERT_TRUE(canonical.ok());
  EXPECT_EQ(ea->info.sha256, sha256_hex(canonical->data(), canonical->size()));
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
  for (size_t keep : {size_t{0}, size_t{1}, e->blob.size() / 2, e->blob.size() - 1}) {
    expect_data_loss(e->blob.substr(0, keep), "zlib");
  }
}

TEST(SurfaceBlob, CorruptedBytesAreDataLoss) {
  std::mt19937_64 rng(4);
  auto e = encode_surface(random_mesh(rng, 100, 100));
  ASSERT_TRUE(e.ok());
  // Flip a byte in the middle: zlib's adler32 (or the stream structure) catches it.
  std::string blob = e->blob;
  blob[blob.size() / 2] = char(blob[blob.size() / 2] ^ 0x5a);
  expect_data_loss(blob, "");
  expect_data_loss(e->blob + "x", "after its zlib stream");
  expect_data_loss("not a blob at all", "");
}

// Builds a blob from canonical bytes written by hand, to reach the checks behind zlib.
std::string blob_of(const std::string& canonical) { return *deflate_bytes(canonical.data(), canonical.size()); }

std::string header(uint32_t version, uint64_t nv, uint64_t nt) {
  std::string h("SOIQSURF", 8);
  h.append(reinterpret_cast<const char*>(&version), 4);
  h.append(4, '\0');
  h.append(reinterpret_cast<const char*>(&nv), 8);
  h.append(reinterpret_cast<const char*>(&nt), 8);
  return h;
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
