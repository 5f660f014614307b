#pragma once
// zlib compression of stored blobs (surface_blob.h, image_blob.h).

#include <cstddef>
#include <string>

#include "core/base/status.h"

namespace soiq::db {

// zlib stream (RFC 1950) of `size` bytes at `data`. INTERNAL only if zlib fails (out of memory).
Result<std::string> deflate_bytes(const void* data, size_t size);

// The bytes of a zlib stream. DATA_LOSS when the stream is corrupt, truncated, followed by extra
// bytes, or inflates to more than `max_size` bytes (a guard against a corrupt or hostile blob
// asking for unbounded memory).
Result<std::string> inflate_bytes(const std::string& blob, size_t max_size);

}  // namespace soiq::db
