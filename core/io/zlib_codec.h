#pragma once
// zlib and gzip streams for the image formats that compress their voxels (NRRD `encoding: gzip`,
// MetaImage `CompressedData = True`).

#include <cstddef>
#include <string>
#include <string_view>

#include "core/base/status.h"

namespace soiq {

// Inflates a zlib or gzip stream (detected from its header; concatenated gzip members are joined)
// into exactly `expected_bytes` bytes.
// Errors  INVALID_ARGUMENT naming `name` when the stream is corrupt or ends before
//         `expected_bytes` ("truncated"), or holds more than that.
// Cost    O(output); thread-safe.
Result<std::string> inflate_bytes(std::string_view compressed, size_t expected_bytes, const std::string& name);

// The first `max_bytes` bytes a zlib or gzip stream inflates to (fewer when it is shorter), for
// formats whose header tells the size only once inflated (.nii.gz): the header is inflated first,
// then the data up to the size the checked header allows. Never allocates more than `max_bytes`.
// Errors  INVALID_ARGUMENT naming `name` when the stream is corrupt. Cost O(output); thread-safe.
Result<std::string> inflate_at_most(std::string_view compressed, size_t max_bytes, const std::string& name);

enum class ZlibFormat { kZlib, kGzip };

// Deflates `data` at zlib's default level into a zlib (MetaImage) or gzip (NRRD) stream.
// Errors  INTERNAL when zlib fails (out of memory). Cost O(input); thread-safe.
Result<std::string> deflate_bytes(std::string_view data, ZlibFormat format);

}  // namespace soiq
