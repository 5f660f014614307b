#pragma once
// The stored form of an image series' voxels: float32 little-endian in i-fastest order, in the
// delta-planes codec (db/delta_planes.h; version 2, "SOIQIMG2"), which decodes several times faster
// than the zlib of version 1: a cold query decodes each study's image. Version 1 blobs still decode.
// The geometry lives in the series record (SeriesRecord::geometry), not in the blob; the sha256 is
// over the geometry's canonical text (describe-independent: origin, spacing, dims, direction as
// %.17g, and an unevenly spaced grid's slice positions) and the raw voxel bytes, so the same image
// on another grid is a different image.
//
// decode_image(encode_image(img).blob, img.geometry) == img exactly.
// Errors: DATA_LOSS for a truncated or corrupt blob or one whose size does not match the geometry.
// Every version is checked on decode: version 2 by its own Adler-32 of the voxels ("checksum
// differs"), version 1 by the Adler-32 of its zlib stream.

#include <string>

#include "core/base/image.h"
#include "core/base/status.h"

namespace soiq::db {

struct EncodedImage {
  std::string blob;
  std::string sha256;
};

Result<EncodedImage> encode_image(const Image& image);
Result<Image> decode_image(const std::string& blob, const ImageGeometry& geometry);

// True for a version-1 (zlib) blob.
bool is_deflated_image_blob(const std::string& blob);

// The sha256 of the image (EncodedImage::sha256) without encoding it: what soiq-admin verify
// checks a decoded blob against.
std::string image_sha256(const Image& image);

}  // namespace soiq::db
