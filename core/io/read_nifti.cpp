#include "core/io/read_nifti.h"

#include <nifti2_io.h>

#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>

#include "core/io/geometry_from_axes.h"
#include "core/io/read_file_bytes.h"
#include "core/io/voxel_type.h"
#include "core/io/zlib_codec.h"

namespace soiq {
namespace {

struct NiftiFree {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};
using NiftiPtr = std::unique_ptr<nifti_image, NiftiFree>;

std::optional<VoxelType> nifti_voxel_type(int datatype) {
  switch (datatype) {
    case DT_UINT8:
      return VoxelType::kUint8;
    case DT_INT8:
      return VoxelType::kInt8;
    case DT_UINT16:
      return VoxelType::kUint16;
    case DT_INT16:
      return VoxelType::kInt16;
    case DT_UINT32:
      return VoxelType::kUint32;
    case DT_INT32:
      return VoxelType::kInt32;
    case DT_FLOAT32:
      return VoxelType::kFloat32;
    case DT_FLOAT64:
      return VoxelType::kFloat64;
    default:
      return std::nullopt;
  }
}

Result<ImageGeometry> nifti_geometry(const nifti_image& nim, const std::string& path) {
  Mat3 axes{};
  Vec3 origin{0, 0, 0};
  if (nim.qform_code > 0 || nim.sform_code > 0) {
    // libnifti has already built qto_xyz from the quaternion, qfac and pixdim.
    const nifti_dmat44& m = nim.qform_code > 0 ? nim.qto_xyz : nim.sto_xyz;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) axes[r][c] = m.m[r][c];
      origin[r] = m.m[r][3];
    }
  } else {
    // Method 1 (Analyze compatibility). A zero or missing pixdim is common in such files: use 1 mm.
    const double d[3] = {nim.dx, nim.dy, nim.dz};
    for (int a = 0; a < 3; ++a) axes[a][a] = std::isfinite(d[a]) && d[a] > 0 ? d[a] : 1.0;
  }
  // RAS -> LPS.
  for (int r = 0; r < 2; ++r) {
    origin[r] = -origin[r];
    for (int c = 0; c < 3; ++c) axes[r][c] = -axes[r][c];
  }
  // Sizes beyond dim[0] are unused by the standard and count as 1, whatever the file holds there (a
  // 0 there made an empty grid that later steps did not expect).
  std::array<int64_t, 3> dims{1, 1, 1};
  for (int a = 1; a <= 3; ++a) {
    if (nim.dim[0] >= a) dims[size_t(a - 1)] = nim.dim[a];
  }
  return geometry_from_axes(axes, origin, dims, path);
}

bool is_gzip(std::string_view bytes) {
  return bytes.size() >= 2 && uint8_t(bytes[0]) == 0x1f && uint8_t(bytes[1]) == 0x8b;
}

uint32_t byte_swapped(uint32_t v) { return __builtin_bswap32(v); }

// The header's version (1: 348 bytes, 2: 540 bytes) from sizeof_hdr, in either byte order; 0 when
// it is neither, so the bytes are no NIfTI header at all.
int header_version(std::string_view bytes) {
  if (bytes.size() < 4) return 0;
  uint32_t n = 0;
  std::memcpy(&n, bytes.data(), 4);
  if (n == 348 || byte_swapped(n) == 348) return 1;
  if (n == 540 || byte_swapped(n) == 540) return 2;
  return 0;
}

// libnifti builds the nifti_image (qform/sform matrices, byte order) from a header in memory, but
// trusts dim[]: dim[0] indexes the array, so it is checked here first, in the file's byte order.
template <typename Header, typename Dim>
Status check_dims(const Header& h, bool swapped, const std::string& name) {
  Dim d[8];
  std::memcpy(d, h.dim, sizeof d);
  if (swapped) {
    for (Dim& v : d) {
      if constexpr (sizeof(Dim) == 2)
        v = Dim(__builtin_bswap16(uint16_t(v)));
      else
        v = Dim(__builtin_bswap64(uint64_t(v)));
    }
  }
  if (d[0] < 1 || d[0] > 7) {
    return invalid_argument("NIfTI '" + name + "' has dim[0] = " + std::to_string(d[0]) + " (must be 1 to 7)");
  }
  for (int a = 1; a <= d[0]; ++a) {
    if (d[a] < 1) {
      return invalid_argument("NIfTI '" + name + "' has dim[" + std::to_string(a) + "] = " + std::to_string(d[a]) +
                              " (sizes must be >= 1)");
    }
  }
  return ok_status();
}

// The header of version 1 or 2 copied out of `head` (long enough), once its magic says it is a
// single file ("n+1"/"n+2") and its dims are sane. A two-file header ("ni1"/"ni2", or Analyze
// without magic) names a companion .img file: soiq reads self-contained files only, so no header
// can make it open another file.
template <typename Header, typename Dim>
Result<Header> single_file_header(std::string_view head, bool swapped, const std::string& name) {
  constexpr int version = sizeof(Header) == sizeof(nifti_1_header) ? 1 : 2;
  Header h;
  std::memcpy(&h, head.data(), sizeof h);
  const char magic[4] = {'n', '+', char('0' + version), '\0'};
  if (std::memcmp(h.magic, magic, 4) != 0) {
    return invalid_argument("NIfTI '" + name + "' is not a single-file NIfTI-" + std::to_string(version) +
                            " (magic is not '" + magic +
                            "'); a .hdr/.img pair is not read: convert it to one .nii file");
  }
  SOIQ_RETURN_IF_ERROR((check_dims<Header, Dim>(h, swapped, name)));
  return h;
}

// A single-file NIfTI header read from memory into libnifti's image description (no data), with
// vox_offset as the file says it (libnifti silently moves an offset inside the header to 352).
struct NiftiHeader {
  NiftiPtr nim;
  int64_t vox_offset = 0;
  int64_t header_size = 0;
};

Result<NiftiHeader> header_from_bytes(std::string_view head, const std::string& name) {
  const int version = header_version(head);
  if (version == 0) {
    return invalid_argument("'" + name + "' is not a NIfTI file (its first 4 bytes are not sizeof_hdr 348 or 540)");
  }
  const size_t header_size = version == 1 ? sizeof(nifti_1_header) : sizeof(nifti_2_header);
  if (head.size() < header_size) {
    return invalid_argument("NIfTI '" + name + "' is truncated: " + std::to_string(head.size()) +
                            " bytes, less than its " + std::to_string(header_size) + "-byte header");
  }
  uint32_t sizeof_hdr = 0;
  std::memcpy(&sizeof_hdr, head.data(), 4);
  const bool swapped = sizeof_hdr != header_size;
  if (version == 1) {
    SOIQ_ASSIGN_OR_RETURN(const nifti_1_header h, (single_file_header<nifti_1_header, int16_t>(head, swapped, name)));
    // NIfTI-1 stores vox_offset as a float, which libnifti casts to an integer: out of range, that
    // cast is undefined, so it is checked first.
    uint32_t raw_offset = 0;
    std::memcpy(&raw_offset, &h.vox_offset, 4);
    if (swapped) raw_offset = byte_swapped(raw_offset);
    float vox_offset = 0;
    std::memcpy(&vox_offset, &raw_offset, 4);
    if (!(vox_offset >= 0 && vox_offset < 1e15f)) {
      return invalid_argument("NIfTI '" + name + "' has vox_offset " + std::to_string(vox_offset) +
                              " (must be a byte offset within the file)");
    }
    NiftiPtr nim(nifti_convert_n1hdr2nim(h, name.c_str()));
    if (!nim) return invalid_argument("'" + name + "' has a NIfTI-1 header that libnifti rejects");
    return NiftiHeader{std::move(nim), int64_t(vox_offset), int64_t(header_size)};
  }
  SOIQ_ASSIGN_OR_RETURN(const nifti_2_header h, (single_file_header<nifti_2_header, int64_t>(head, swapped, name)));
  int64_t vox_offset = h.vox_offset;
  if (swapped) vox_offset = int64_t(__builtin_bswap64(uint64_t(vox_offset)));
  NiftiPtr nim(nifti_convert_n2hdr2nim(h, name.c_str()));
  if (!nim) return invalid_argument("'" + name + "' has a NIfTI-2 header that libnifti rejects");
  return NiftiHeader{std::move(nim), vox_offset, int64_t(header_size)};
}

}  // namespace

Result<Image> parse_nifti(std::string_view bytes, const std::string& name, const ImageDecodeLimits& limits) {
  if (bytes.empty()) return invalid_argument("image '" + name + "' is empty");
  // libnifti prints its errors to stderr unless its debug level is 0; we report our own.
  static std::once_flag quiet;
  std::call_once(quiet, [] { nifti_set_debug_level(0); });

  const bool gz = is_gzip(bytes);
  std::string inflated_head;
  if (gz) {
    SOIQ_ASSIGN_OR_RETURN(inflated_head, inflate_at_most(bytes, sizeof(nifti_2_header), name));
  }
  SOIQ_ASSIGN_OR_RETURN(const NiftiHeader header,
                        header_from_bytes(gz ? std::string_view(inflated_head) : bytes, name));
  const NiftiPtr& nim = header.nim;
  for (int d = 4; d <= 7; ++d) {
    if (nim->dim[0] >= d && nim->dim[d] > 1) {
      return invalid_argument("NIfTI '" + name + "' has " + std::to_string(nim->dim[0]) +
                              " dimensions; soiq reads 3D images only");
    }
  }
  const auto type = nifti_voxel_type(nim->datatype);
  if (!type) {
    return invalid_argument("NIfTI '" + name + "' has datatype " + std::to_string(nim->datatype) + " (" +
                            nifti_datatype_string(nim->datatype) + "), which soiq does not read");
  }
  SOIQ_ASSIGN_OR_RETURN(const ImageGeometry geometry, nifti_geometry(*nim, name));
  SOIQ_RETURN_IF_ERROR(check_before_decoding(geometry, voxel_type_size(*type), limits));
  const int64_t count = geometry.voxel_count();
  const int64_t needed = count * int64_t(voxel_type_size(*type));
  // vox_offset is where the voxels start; it cannot lie inside the header, nor past the data.
  const int64_t header_size = header.header_size;
  const int64_t offset = header.vox_offset;
  if (offset < 0 || offset > (int64_t(1) << 50)) {
    return invalid_argument("NIfTI '" + name + "' has vox_offset " + std::to_string(offset) +
                            " (must be a byte offset within the file)");
  }
  if (offset < header_size) {
    return invalid_argument("NIfTI '" + name + "' has vox_offset " + std::to_string(offset) +
                            ", inside its header (a single-file NIfTI's voxels start at byte " +
                            std::to_string(header_size) + " or later)");
  }
  std::string inflated;
  if (gz) {
    SOIQ_ASSIGN_OR_RETURN(inflated, inflate_at_most(bytes, size_t(offset + needed), name));
  }
  const std::string_view file = gz ? std::string_view(inflated) : bytes;
  if (int64_t(file.size()) < offset + needed) {
    return invalid_argument("NIfTI '" + name + "' is truncated: " + std::to_string(file.size()) +
                            " bytes, its header (vox_offset " + std::to_string(offset) + ", " + std::to_string(count) +
                            " voxels of " + std::to_string(voxel_type_size(*type)) + " bytes) needs " +
                            std::to_string(offset + needed));
  }
  const bool swap = nim->byteorder != nifti_short_order();
  Image image{geometry, decode_voxels(file.data() + offset, size_t(count), *type, swap)};
  const double slope = nim->scl_slope;
  const double inter = nim->scl_inter;
  if (std::isfinite(slope) && slope != 0 && std::isfinite(inter) && !(slope == 1 && inter == 0)) {
    for (float& v : image.voxels) {
      const bool was_finite = std::isfinite(v);
      v = float(double(v) * slope + inter);
      if (was_finite && !std::isfinite(v)) {
        return invalid_argument("NIfTI '" + name + "' has scl_slope " + std::to_string(slope) + " and scl_inter " +
                                std::to_string(inter) + ", which take its voxel values beyond float's range");
      }
    }
  }
  return image;
}

Result<Image> read_nifti(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(const std::string bytes, read_file_bytes(path, "image"));
  return parse_nifti(bytes, path, {});
}

}  // namespace soiq
