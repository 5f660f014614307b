#pragma once
// Reads a 3D MetaImage (.mha with LOCAL data, or .mhd with a separate ElementDataFile); the
// MetaImage branch of read_image (see read_image.h for the shared contract).
//
// Geometry    Offset (or Position, or Origin) is voxel (0,0,0) in LPS; ElementSpacing; and
//             TransformMatrix (or Rotation, or Orientation), whose 9 numbers are the direction
//             matrix's columns one after the other — the unit direction of axis i first — as
//             ITK's MetaImageIO writes them (transformMatrix[i*3+j] = GetDirection(i)[j]).
//             AnatomicalOrientation is ignored: the coordinates are taken as LPS, as ITK does.
// Supported   ObjectType Image, NDims 3, one channel, ElementType MET_UCHAR, MET_CHAR, MET_USHORT,
//             MET_SHORT, MET_UINT, MET_INT, MET_FLOAT, MET_DOUBLE; BinaryDataByteOrderMSB;
//             CompressedData (zlib); HeaderSize for raw data files (-1: data at the end).
// Errors      NOT_FOUND header or data file missing; INVALID_ARGUMENT malformed or unsupported header
//             fields (named), truncated or corrupt data; RESOURCE_EXHAUSTED > kDefaultMaxVoxels.
// Cost        O(voxels); thread-safe.

#include <optional>
#include <string>

#include "core/base/image.h"
#include "core/base/status.h"
#include "core/io/image_decode_limits.h"

namespace soiq {

Result<Image> read_metaimage(const std::string& path);

// The same from bytes named `path` in messages; `detached_dir` as for parse_nrrd: nullopt refuses
// any ElementDataFile but LOCAL.
Result<Image> parse_metaimage(const std::string& bytes, const std::string& path,
                              const std::optional<std::string>& detached_dir, const ImageDecodeLimits& limits);

}  // namespace soiq
