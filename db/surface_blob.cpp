#include "db/surface_blob.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <limits>

#include "db/deflate.h"

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

  std::string canonical(kHeaderSize + nv * 3 * sizeof(double) + nt * 3 * sizeof(uint32_t), '\0');
  size_t at = 0;
  std::memcpy(canonical.data(), kMagic, sizeof kMagic);
  at += sizeof kMagic;
  put(canonical, at, kVersion);
  put(canonical, at, uint32_t{0});
  put(canonical, at, uint64_t(nv));
  put(canonical, at, uint64_t(nt));
  // Vec3 is std::array<double, 3> and the triangles std::array<int32_t, 3>: contiguous, so the
  // payload is two block copies (int32 >= 0 has the same bytes as uint32).
  if (nv > 0) std::memcpy(canonical.data() + at, mesh.vertices_mm.data(), nv * 3 * sizeof(double));
  at += nv * 3 * sizeof(double);
  if (nt > 0) std::memcpy(canonical.data() + at, mesh.triangles.data(), nt * 3 * sizeof(uint32_t));

  info.sha256 = sha256_hex(canonical.data(), canonical.size());
  SOIQ_ASSIGN_OR_RETURN(out.blob, deflate_bytes(canonical.data(), canonical.size()));
  return out;
}

Result<TriangleMesh> decode_surface(const std::string& blob) {
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
  for (size_t t = 0; t < nt; ++t) {
    for (int32_t v : mesh.triangles[t]) {
      // A stored index >= 2^31 reads back negative: out of range as well.
      if (v < 0 || uint64_t(v) >= nv) {
        return data_loss("surface blob triangle " + std::to_string(t) + " refers to vertex " +
                         std::to_string(uint32_t(v)) + " of " + std::to_string(nv));
      }
    }
  }
  return mesh;
}

}  // namespace soiq::db
