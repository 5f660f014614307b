#pragma once
// Reads a 3D NRRD image (.nrrd with attached data, or .nhdr with a detached `data file`); the
// NRRD branch of read_image (see read_image.h for the contract shared by all formats).
//
// Supported   `type` int8..uint32, float, double; `dimension: 3`; `encoding` raw, gzip or ascii;
//             `endian`; `space` LPS, RAS or LAS (converted to LPS) or absent (taken as LPS);
//             `space directions` (else `spacings`, else unit axes); `space origin`; `byte skip`
//             >= 0 or -1 for raw data.
// Errors      NOT_FOUND header or data file missing; INVALID_ARGUMENT malformed header (the
//             message names the field), unsupported field values, truncated or corrupt data;
//             RESOURCE_EXHAUSTED more than kDefaultMaxVoxels voxels.
// Cost        O(voxels); thread-safe.

#include <optional>
#include <string>

#include "core/base/image.h"
#include "core/base/status.h"
#include "core/io/image_decode_limits.h"

namespace soiq {

Result<Image> read_nrrd(const std::string& path);

// The same from bytes named `path` in messages. `detached_dir`: the directory a `data file` field
// is resolved in (with a trailing '/'), or nullopt for bytes that are not a local file (an
// upload): a header naming a data file is then INVALID_ARGUMENT, so no header can make soiqd read
// a file of the sender's choosing.
Result<Image> parse_nrrd(const std::string& bytes, const std::string& path,
                         const std::optional<std::string>& detached_dir, const ImageDecodeLimits& limits);

}  // namespace soiq
