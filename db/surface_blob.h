#pragma once
// The stored form of a surface model: canonical and compressed, so the same mesh uploaded twice
// (in any file format) is stored once, and checked, so a damaged blob is refused, never read as
// another mesh.
//
// Canonical encoding: a magic tag and version, vertex and triangle counts, then the vertices as
// little-endian float64 LPS millimetres and the triangles as little-endian uint32 index triples,
// exactly as the mesh holds them (no reordering: the uploaded mesh is what is stored). The sha256
// is taken over these canonical bytes, so it names the mesh whatever the blob's codec (and the
// store's dedupe by sha256 does not depend on it).
//
// The blob (version 3, "SOIQSRC3") holds the x, y and z planes and the three corner planes as
// delta-planes streams (delta_planes.h), after a CRC-32 (crc32.h) of every byte that follows it,
// which decode_surface checks before anything else. Older blobs still decode: version 2
// ("SOIQSRF2", the same streams without the checksum: nothing of its own notices a flipped bit)
// and version 1 (the canonical bytes deflated, checked by zlib's Adler-32). The schema migrations
// re-encode them in version 3 (SQLite's version 9, PostgreSQL's version 5: db/sql/checksum_stored_bytes.h).
//
// decode_surface(encode_surface(m).blob) == m exactly (bitwise coordinates, same indices).
// Errors: decode_surface gives DATA_LOSS for a blob whose checksum differs ("checksum mismatch"),
// that is not a surface blob, is truncated, claims more than it can hold, or whose indices are out
// of range. It knows only the blob: a caller that knows the structure names it in the message.
// Cost: decode O(size); the checksum adds ~14 % to a version 2 decode (zlib's crc32 at ~6 GB/s:
// 0.29 ms on a 400k-triangle surface).

#include <string>
#include <string_view>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "db/store.h"

namespace soiq::db {

struct EncodedSurface {
  std::string blob;  // compressed canonical bytes
  SurfaceInfo info;  // sha256 (lower-case hex), counts and bounds
};

Result<EncodedSurface> encode_surface(const TriangleMesh& mesh);
Result<TriangleMesh> decode_surface(const std::string& blob);

// 3 for a blob with a checksum, 2 or 1 for one of the older versions (1: anything that does not
// start with a magic of the others, which decode_surface reads as zlib).
int surface_blob_version(std::string_view blob);
// True for a version 1 (zlib) blob.
bool is_deflated_surface_blob(const std::string& blob);

// The sha256 of the mesh's canonical bytes (SurfaceInfo::sha256, what encode_surface gives),
// without encoding it: what a blob without a checksum is checked against, and what
// soiq-admin verify checks every decoded blob against.
std::string surface_sha256(const TriangleMesh& mesh);

// Lower-case hex sha256 of bytes (OpenSSL).
std::string sha256_hex(const void* data, size_t size);

}  // namespace soiq::db
