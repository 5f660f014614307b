#include "db/surface_blob.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/voxelize/memory_estimate.h"
#include "db/deflate.h"
#include "db/delta_planes.h"

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

// Version 1's canonical bytes of `m`: what the sha256 is taken over, and deflated, a version 1 blob.
std::string canonical_bytes(const TriangleMesh& m) {
  std::string c = header(1, m.vertices_mm.size(), m.triangles.size());
  c.append(reinterpret_cast<const char*>(m.vertices_mm.data()), m.vertices_mm.size() * sizeof(Vec3));
  c.append(reinterpret_cast<const char*>(m.triangles.data()), m.triangles.size() * 12);
  return c;
}

void expect_data_loss(const std::string& blob, const std::string& phrase);

// The version 2 blob of the same mesh: version 3 without its checksum, under version 2's magic
// (db/surface_blob.cpp: magic, CRC-32, then what version 2 holds after its magic).
std::string version2_of(const std::string& v3) { return std::string("SOIQSRF2", 8) + v3.substr(12); }

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
  TriangleMesh m;
  const int rings = 120, segments = 240;
  for (int r = 0; r <= rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const double th = 3.14159265358979 * r / rings, ph = 2 * 3.14159265358979 * s / segments;
      m.vertices_mm.push_back({20 * std::sin(th) * std::cos(ph), 20 * std::sin(th) * std::sin(ph), 20 * std::cos(th)});
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      m.triangles.push_back({a, b, a + segments});
      m.triangles.push_back({b, b + segments, a + segments});
    }
  }
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

// --- version 3: a CRC-32 over every stored byte ------------------------------------------------

TEST(SurfaceBlob, NewBlobsAreVersion3AndTheVersion2BlobOfTheSameMeshStillDecodes) {
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

TEST(SurfaceBlob, TheShaOfAMeshIsTheOneItsEncodingGivesWithoutEncodingIt) {
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

TEST(SurfaceBlob, EveryFlippedBitOfASmallVersion3BlobIsDataLoss) {
  std::mt19937_64 rng(23);
  auto e = encode_surface(random_mesh(rng, 12, 20));
  ASSERT_TRUE(e.ok());
  std::string blob = e->blob;
  for (size_t at = 0; at < blob.size(); ++at)
    for (int bit = 0; bit < 8; ++bit) expect_flip_refused(blob, at, bit);
  EXPECT_TRUE(decode_surface(blob).ok());  // every bit flipped back
}

// A smooth sphere of `rings` x 240 vertices: its planes compress, so its blocks are LZ4's.
TriangleMesh smooth_sphere(int rings) {
  const int segments = 240;
  TriangleMesh m;
  for (int r = 0; r <= rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const double th = 3.14159265358979 * r / rings, ph = 2 * 3.14159265358979 * s / segments;
      m.vertices_mm.push_back({20 * std::sin(th) * std::cos(ph), 20 * std::sin(th) * std::sin(ph), 20 * std::cos(th)});
    }
  }
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      m.triangles.push_back({a, b, a + segments});
      m.triangles.push_back({b, b + segments, a + segments});
    }
  }
  return m;
}

// Meshes of more than one 512 KiB block per plane (65536 float64, 131072 int32), smooth and random
// (LZ4 blocks), and a small random one whose blocks LZ4 cannot shrink, stored as they are: the case
// where a flipped bit in a version 2 blob reads as another coordinate. Every bit of the header
// (magic, checksum, counts), of each block's size word, and of the first, middle and last byte of
// each block of each plane stream is flipped in turn, and the last byte of the blob.
TEST(SurfaceBlob, FlippedBitsInEachPartOfVersion3BlobsAreDataLoss) {
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
