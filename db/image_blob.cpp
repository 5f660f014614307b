#include "db/image_blob.h"

#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "db/deflate.h"
#include "db/delta_planes.h"
#include "db/sha256.h"

namespace soiq::db {
namespace {

static_assert(std::endian::native == std::endian::little, "image blobs assume a little-endian host");
static_assert(std::numeric_limits<float>::is_iec559, "image blobs store IEEE float32");

// The geometry part of the hash: every field at %.17g (round-trips a double), in a fixed order.
std::string canonical_geometry_text(const ImageGeometry& g) {
  char buf[1024];
  const auto& d = g.direction;
  std::snprintf(buf, sizeof buf,
                "origin %.17g %.17g %.17g\nspacing %.17g %.17g %.17g\ndims %" PRId64 " %" PRId64 " %" PRId64
                "\ndirection %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n",
                g.origin_mm[0], g.origin_mm[1], g.origin_mm[2], g.spacing_mm[0], g.spacing_mm[1], g.spacing_mm[2],
                g.dims[0], g.dims[1], g.dims[2], d[0][0], d[0][1], d[0][2], d[1][0], d[1][1], d[1][2], d[2][0], d[2][1],
                d[2][2]);
  // Only an unevenly spaced grid says where its slices are: every other image keeps its sha256.
  std::string out = buf;
  if (g.uneven()) {
    out += "slices";
    for (const double p : g.slice_positions_mm) {
      std::snprintf(buf, sizeof buf, " %.17g", p);
      out += buf;
    }
    out += '\n';
  }
  return out;
}

// Version 2: this magic, the Adler-32 of the raw voxel bytes (little-endian uint32), then the voxels'
// float32 bit patterns in the delta-planes codec. The checksum is what zlib's stream had: a block
// LZ4 could not shrink is stored as is, and a flipped bit in it would otherwise decode to a wrong
// voxel without a word. Version 1 was the raw bytes deflated by zlib (a zlib stream never starts with
// 'S'), and still decodes.
constexpr char kPlanesMagic[8] = {'S', 'O', 'I', 'Q', 'I', 'M', 'G', '2'};

uint32_t voxel_checksum(const std::vector<float>& voxels) {
  // zlib's adler32 takes a uInt length: feed it in pieces.
  uLong sum = adler32(0L, Z_NULL, 0);
  const auto* bytes = reinterpret_cast<const Bytef*>(voxels.data());
  size_t left = voxels.size() * sizeof(float);
  while (left > 0) {
    const uInt n = uInt(std::min<size_t>(left, size_t(1) << 30));
    sum = adler32(sum, bytes, n);
    bytes += n;
    left -= n;
  }
  return uint32_t(sum);
}

bool has_planes_magic(const std::string& blob) {
  return blob.size() >= sizeof kPlanesMagic && std::memcmp(blob.data(), kPlanesMagic, sizeof kPlanesMagic) == 0;
}

}  // namespace

bool is_deflated_image_blob(const std::string& blob) { return !has_planes_magic(blob); }

std::string image_sha256(const Image& image) {
  Sha256 hasher;
  const std::string text = canonical_geometry_text(image.geometry);
  hasher.update(text.data(), text.size());
  hasher.update(image.voxels.data(), image.voxels.size() * sizeof(float));
  return hasher.hex_digest();
}

Result<EncodedImage> encode_image(const Image& image) {
  const auto& dims = image.geometry.dims;
  if (dims[0] < 0 || dims[1] < 0 || dims[2] < 0 || image.voxels.size() != size_t(image.geometry.voxel_count())) {
    return invalid_argument("image has " + std::to_string(image.voxels.size()) + " voxels but its grid is " +
                            describe(image.geometry));
  }
  EncodedImage out;
  out.sha256 = image_sha256(image);
  out.blob.assign(kPlanesMagic, sizeof kPlanesMagic);
  const uint32_t sum = voxel_checksum(image.voxels);
  out.blob.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  append_delta_planes(image.voxels.data(), image.voxels.size(), 4, sizeof(float), out.blob);
  return out;
}

Result<Image> decode_image(const std::string& blob, const ImageGeometry& geometry) {
  const auto& dims = geometry.dims;
  if (dims[0] < 0 || dims[1] < 0 || dims[2] < 0) return invalid_argument("image grid has negative dimensions");
  // Multiply in double first: the product of three int64 can overflow.
  const double count = double(dims[0]) * double(dims[1]) * double(dims[2]);
  if (count * sizeof(float) > double(std::numeric_limits<size_t>::max() / 2)) {
    return data_loss("image grid " + describe(geometry) + " is too large for an image blob");
  }
  const size_t expected = size_t(geometry.voxel_count()) * sizeof(float);
  if (has_planes_magic(blob)) {
    Image image;
    image.geometry = geometry;
    image.voxels.resize(size_t(geometry.voxel_count()));
    uint32_t sum = 0;
    if (blob.size() < sizeof kPlanesMagic + sizeof sum) return data_loss("image blob is truncated");
    std::memcpy(&sum, blob.data() + sizeof kPlanesMagic, sizeof sum);
    size_t at = sizeof kPlanesMagic + sizeof sum;
    const Status read = read_delta_planes(blob, at, image.voxels.size(), 4, sizeof(float), image.voxels.data());
    if (!read.ok()) return Status(read.code(), "image " + read.message());
    if (at != blob.size()) return data_loss("image blob has " + std::to_string(blob.size() - at) + " extra bytes");
    if (voxel_checksum(image.voxels) != sum) return data_loss("image blob is corrupt (its checksum differs)");
    return image;
  }
  SOIQ_ASSIGN_OR_RETURN(std::string raw, inflate_bytes(blob, expected));
  if (raw.size() != expected) {
    return data_loss("image blob holds " + std::to_string(raw.size()) + " bytes but its grid " + describe(geometry) +
                     " needs " + std::to_string(expected));
  }
  Image image;
  image.geometry = geometry;
  image.voxels.resize(size_t(geometry.voxel_count()));
  if (expected > 0) std::memcpy(image.voxels.data(), raw.data(), expected);
  return image;
}

}  // namespace soiq::db
