#include "db/surface_blob.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string_view>

#include "core/voxelize/memory_estimate.h"
#include "db/crc32.h"
#include "db/deflate.h"
#include "db/delta_planes.h"
#include "db/sha256.h"

namespace soiq::db {
namespace {

// The canonical bytes are little-endian. Every platform we build for is; a big-endian port would
// byte-swap in put/get below and nowhere else.
static_assert(std::endian::native == std::endian::little, "surface blobs assume a little-endian host");

constexpr char kMagic[8] = {'S', 'O', 'I', 'Q', 'S', 'U', 'R', 'F'};
constexpr uint32_t kVersion = 1;
// magic, version, reserved (0), vertex count, triangle count
constexpr size_t kHeaderSize = 8 + 4 + 4 + 8 + 8;
// A blob may not claim more than this many canonical bytes (16 GiB): a corrupt header must not
// make us allocate without bound.
constexpr size_t kMaxCanonicalBytes = size_t{16} << 30;

template <typename T>
void put(std::string& out, size_t& at, const T& v) {
  std::memcpy(out.data() + at, &v, sizeof v);
  at += sizeof v;
}

template <typename T>
T get(const std::string& in, size_t at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof v);
  return v;
}

// The blob of version 2: the magic, the counts, then the x, y and z coordinates of every vertex and
// the first, second and third corner of every triangle, each as a delta-planes stream
// (delta_planes.h). Neighbouring vertices share their high bytes, and corners their neighbours'
// indices, so the streams are mostly zero runs; LZ4 decodes them at memory speed.
constexpr char kPlanesMagic[8] = {'S', 'O', 'I', 'Q', 'S', 'R', 'F', '2'};
// Version 3: version 2 with the CRC-32 (crc32.h) of every byte after it, right after the magic:
// magic, checksum, counts, streams. A block LZ4 could not shrink is stored as is, and a flipped bit
// in a coordinate's high bytes decodes to a vertex elsewhere, so without it a damaged blob can
// decode to a plausible mesh. The magic differs from version 2's in three bits ('C' for checked,
// '3'), so no flipped bit turns a version 3 blob into an unchecked version 2 one; a version 3 blob
// with any other damage to its magic reads as zlib, which refuses it at its first byte.
constexpr char kCheckedMagic[8] = {'S', 'O', 'I', 'Q', 'S', 'R', 'C', '3'};
constexpr size_t kChecksumAt = 8;
constexpr size_t kCheckedHeaderSize = 8 + 4 + 8 + 8;
// LZ4 expands at most 255-fold: a header claiming more than that of the blob's size is corrupt,
// and is refused before anything that large is allocated.
constexpr size_t kMaxExpansion = 255;

bool has_magic(std::string_view blob, const char (&magic)[8]) {
  return blob.size() >= sizeof magic && std::memcmp(blob.data(), magic, sizeof magic) == 0;
}

std::string encode_planes(const TriangleMesh& mesh) {
  const size_t nv = mesh.vertices_mm.size(), nt = mesh.triangles.size();
  std::string out(kCheckedHeaderSize, '\0');
  size_t at = 0;
  std::memcpy(out.data(), kCheckedMagic, sizeof kCheckedMagic);
  at += sizeof kCheckedMagic + sizeof(uint32_t);  // the checksum, written last
  put(out, at, uint64_t(nv));
  put(out, at, uint64_t(nt));
  for (int a = 0; a < 3; ++a) {
    append_delta_planes(nv ? &mesh.vertices_mm[0][a] : nullptr, nv, 8, sizeof(Vec3), out);
  }
  for (int k = 0; k < 3; ++k) {
    append_delta_planes(nt ? &mesh.triangles[0][k] : nullptr, nt, 4, sizeof(mesh.triangles[0]), out);
  }
  const uint32_t crc = crc32_of(std::string_view(out).substr(kChecksumAt + sizeof crc));
  at = kChecksumAt;
  put(out, at, crc);
  return out;
}

// Every triangle's corners are vertices of the mesh (a stored index >= 2^31 reads back negative).
Status check_indices(const TriangleMesh& mesh) {
  const uint64_t nv = mesh.vertices_mm.size();
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int32_t v : mesh.triangles[t]) {
      if (v < 0 || uint64_t(v) >= nv) {
        return data_loss("surface blob triangle " + std::to_string(t) + " refers to vertex " +
                         std::to_string(uint32_t(v)) + " of " + std::to_string(nv));
      }
    }
  }
  return ok_status();
}

// The counts at `counts_at`, then the six streams up to the blob's end (versions 2 and 3).
Result<TriangleMesh> decode_planes(const std::string& blob, size_t counts_at) {
  if (blob.size() < counts_at + 16) return data_loss("surface blob is truncated (no header)");
  const auto nv = get<uint64_t>(blob, counts_at);
  const auto nt = get<uint64_t>(blob, counts_at + 8);
  const size_t limit = std::min(kMaxCanonicalBytes, blob.size() * kMaxExpansion);
  if (nv > limit / 24 || nt > limit / 12 || nv * 24 + nt * 12 > limit) {
    return data_loss("surface blob header says " + std::to_string(nv) + " vertices and " + std::to_string(nt) +
                     " triangles, more than its " + std::to_string(blob.size()) + " bytes can hold");
  }
  TriangleMesh mesh;
  mesh.vertices_mm.resize(nv);
  mesh.triangles.resize(nt);
  size_t at = counts_at + 16;
  // The codec's errors speak of "blob": say which.
  auto planes = [&](size_t count, int width, size_t stride, void* values) -> Status {
    const Status read = read_delta_planes(blob, at, count, width, stride, values);
    return read.ok() ? read : Status(read.code(), "surface " + read.message());
  };
  for (int a = 0; a < 3; ++a) SOIQ_RETURN_IF_ERROR(planes(nv, 8, sizeof(Vec3), nv ? &mesh.vertices_mm[0][a] : nullptr));
  for (int k = 0; k < 3; ++k)
    SOIQ_RETURN_IF_ERROR(planes(nt, 4, sizeof(mesh.triangles[0]), nt ? &mesh.triangles[0][k] : nullptr));
  if (at != blob.size()) return data_loss("surface blob has " + std::to_string(blob.size() - at) + " extra bytes");
  SOIQ_RETURN_IF_ERROR(check_indices(mesh));
  return mesh;
}

// Version 3: the checksum first, so that no damaged byte reaches the decoder.
Result<TriangleMesh> decode_checked(const std::string& blob) {
  if (blob.size() < kCheckedHeaderSize) return data_loss("surface blob is truncated (no header)");
  const auto stored = get<uint32_t>(blob, kChecksumAt);
  const uint32_t computed = crc32_of(std::string_view(blob).substr(kChecksumAt + sizeof stored));
  if (computed != stored) {
    char sums[64];
    std::snprintf(sums, sizeof sums, "stored %08x, computed %08x", stored, computed);
    return data_loss("surface blob checksum mismatch (crc32 " + std::string(sums) + ")");
  }
  return decode_planes(blob, kChecksumAt + sizeof stored);
}

Result<TriangleMesh> decode_deflated(const std::string& blob);

}  // namespace

Result<EncodedSurface> encode_surface(const TriangleMesh& mesh) {
  const size_t nv = mesh.vertices_mm.size();
  const size_t nt = mesh.triangles.size();
  if (nv > size_t(std::numeric_limits<int32_t>::max())) {
    return invalid_argument("surface has " + std::to_string(nv) + " vertices; at most 2^31-1 can be stored");
  }
  EncodedSurface out;
  SurfaceInfo& info = out.info;
  info.vertex_count = int64_t(nv);
  info.triangle_count = int64_t(nt);
  for (int a = 0; a < 3; ++a) {
    info.bounds_mm[a] = nv == 0 ? 0.0 : std::numeric_limits<double>::infinity();
    info.bounds_mm[a + 3] = nv == 0 ? 0.0 : -std::numeric_limits<double>::infinity();
  }
  for (size_t i = 0; i < nv; ++i) {
    for (int a = 0; a < 3; ++a) {
      const double x = mesh.vertices_mm[i][a];
      if (!std::isfinite(x)) {
        return invalid_argument("surface vertex " + std::to_string(i) + " has a non-finite coordinate");
      }
      info.bounds_mm[a] = std::min(info.bounds_mm[a], x);
      info.bounds_mm[a + 3] = std::max(info.bounds_mm[a + 3], x);
    }
  }
  for (size_t t = 0; t < nt; ++t) {
    for (int32_t v : mesh.triangles[t]) {
      if (v < 0 || size_t(v) >= nv) {
        return invalid_argument("surface triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                                " of " + std::to_string(nv));
      }
    }
  }

  info.sha256 = surface_sha256(mesh);
  // Coordinates near the largest double overflow the bounds: those stay unknown (0 and 0), so
  // admission measures the mesh itself and refuses it as it always has (SQLite cannot hold a NaN).
  const SurfaceMeasure measure = surface_measure(mesh);
  if (std::isfinite(measure.area_mm2) && std::isfinite(measure.perimeter_mm)) {
    info.area_bound_mm2 = measure.area_mm2;
    info.perimeter_bound_mm = measure.perimeter_mm;
  }
  out.blob = encode_planes(mesh);
  return out;
}

std::string surface_sha256(const TriangleMesh& mesh) {
  const uint64_t nv = mesh.vertices_mm.size(), nt = mesh.triangles.size();
  std::string header(kHeaderSize, '\0');
  size_t at = 0;
  std::memcpy(header.data(), kMagic, sizeof kMagic);
  at += sizeof kMagic;
  put(header, at, kVersion);
  put(header, at, uint32_t{0});
  put(header, at, nv);
  put(header, at, nt);
  // Vec3 is std::array<double, 3> and the triangles std::array<int32_t, 3>: contiguous, so the
  // payload is two blocks, hashed where they lie (int32 >= 0 has the same bytes as uint32).
  Sha256 hash;
  hash.update(header.data(), header.size());
  if (nv > 0) hash.update(mesh.vertices_mm.data(), nv * 3 * sizeof(double));
  if (nt > 0) hash.update(mesh.triangles.data(), nt * 3 * sizeof(uint32_t));
  return hash.hex_digest();
}

Result<TriangleMesh> decode_surface(const std::string& blob) {
  if (has_magic(blob, kCheckedMagic)) return decode_checked(blob);
  if (has_magic(blob, kPlanesMagic)) return decode_planes(blob, sizeof kPlanesMagic);
  return decode_deflated(blob);
}

int surface_blob_version(std::string_view blob) {
  if (has_magic(blob, kCheckedMagic)) return 3;
  return has_magic(blob, kPlanesMagic) ? 2 : 1;
}

bool is_deflated_surface_blob(const std::string& blob) { return surface_blob_version(blob) == 1; }

namespace {

Result<TriangleMesh> decode_deflated(const std::string& blob) {
  SOIQ_ASSIGN_OR_RETURN(std::string canonical, inflate_bytes(blob, kMaxCanonicalBytes));
  if (canonical.size() < kHeaderSize || std::memcmp(canonical.data(), kMagic, sizeof kMagic) != 0) {
    return data_loss("blob is not a soiq surface blob (no SOIQSURF header)");
  }
  const auto version = get<uint32_t>(canonical, 8);
  if (version != kVersion) {
    return data_loss("surface blob has encoding version " + std::to_string(version) + "; this soiqd reads version " +
                     std::to_string(kVersion));
  }
  const auto nv = get<uint64_t>(canonical, 16);
  const auto nt = get<uint64_t>(canonical, 24);
  // Compare counts against the actual size before multiplying, so huge counts cannot overflow.
  const size_t payload = canonical.size() - kHeaderSize;
  if (nv > payload / 24 || nt > payload / 12 || nv * 24 + nt * 12 != payload) {
    return data_loss("surface blob is truncated or padded: header says " + std::to_string(nv) + " vertices and " +
                     std::to_string(nt) + " triangles but it holds " + std::to_string(payload) + " payload bytes");
  }
  TriangleMesh mesh;
  mesh.vertices_mm.resize(nv);
  mesh.triangles.resize(nt);
  if (nv > 0) std::memcpy(mesh.vertices_mm.data(), canonical.data() + kHeaderSize, nv * 24);
  if (nt > 0) std::memcpy(mesh.triangles.data(), canonical.data() + kHeaderSize + nv * 24, nt * 12);
  SOIQ_RETURN_IF_ERROR(check_indices(mesh));
  return mesh;
}

}  // namespace

}  // namespace soiq::db
