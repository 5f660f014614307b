#pragma once
// The stored form of a surface model: canonical and compressed, so the same mesh uploaded twice
// (in any file format) is stored once.
//
// Canonical encoding: a magic tag and version, vertex and triangle counts, then the vertices as
// little-endian float64 LPS millimetres and the triangles as little-endian uint32 index triples,
// exactly as the mesh holds them (no reordering: the uploaded mesh is what is stored). The sha256
// is taken over these canonical bytes, so it names the mesh whatever the blob's codec.
//
// The blob (version 2, "SOIQSRF2") holds the x, y and z planes and the three corner planes as
// delta-planes streams (delta_planes.h): half the size of the zlib blobs of version 1, and decoded
// several times faster, which is most of what a cold query spends per structure. Version 1 blobs
// (the canonical bytes deflated) are still read; the schema migration to version 4 re-encodes them.
//
// decode_surface(encode_surface(m).blob) == m exactly (bitwise coordinates, same indices).
// Errors: decode_surface gives DATA_LOSS for a blob that is not a surface blob, is truncated,
// claims more than it can hold, or whose indices are out of range.

#include <string>

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

// True for a version 1 (zlib) blob, which the migration re-encodes.
bool is_deflated_surface_blob(const std::string& blob);

// Lower-case hex sha256 of bytes (OpenSSL).
std::string sha256_hex(const void* data, size_t size);

}  // namespace soiq::db
