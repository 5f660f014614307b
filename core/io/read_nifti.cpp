#include "core/io/read_nifti.h"

#include <nifti2_io.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <optional>

#include "core/io/geometry_from_axes.h"
#include "core/io/read_file_bytes.h"
#include "core/io/voxel_type.h"

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
  return geometry_from_axes(axes, origin, {nim.nx, nim.ny, nim.nz}, path);
}

}  // namespace

Result<Image> read_nifti(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(const int64_t file_bytes, input_file_size(path, "image"));
  if (file_bytes == 0) return invalid_argument("image file '" + path + "' is empty");
  // libnifti prints its errors to stderr unless its debug level is 0; we report our own.
  static std::once_flag quiet;
  std::call_once(quiet, [] { nifti_set_debug_level(0); });

  NiftiPtr nim(nifti_image_read(path.c_str(), /*read_data=*/0));
  if (!nim) return invalid_argument("'" + path + "' is not a readable NIfTI file (bad or truncated header)");
  for (int d = 4; d <= 7; ++d) {
    if (nim->dim[0] >= d && nim->dim[d] > 1) {
      return invalid_argument("NIfTI '" + path + "' has " + std::to_string(nim->dim[0]) +
                              " dimensions; soiq reads 3D images only");
    }
  }
  const auto type = nifti_voxel_type(nim->datatype);
  if (!type) {
    return invalid_argument("NIfTI '" + path + "' has datatype " + std::to_string(nim->datatype) + " (" +
                            nifti_datatype_string(nim->datatype) + "), which soiq does not read");
  }
  SOIQ_ASSIGN_OR_RETURN(const ImageGeometry geometry, nifti_geometry(*nim, path));
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, kDefaultMaxVoxels));
  const int64_t count = geometry.voxel_count();
  const int64_t needed = count * int64_t(voxel_type_size(*type));
  // For an uncompressed file, check the size before libnifti allocates and reads.
  if (nim->iname && !nifti_is_gzfile(nim->iname)) {
    SOIQ_ASSIGN_OR_RETURN(const int64_t data_file_bytes, input_file_size(nim->iname, "NIfTI data"));
    if (data_file_bytes < nim->iname_offset + needed) {
      return invalid_argument("NIfTI '" + path + "' is truncated: " + std::to_string(data_file_bytes) +
                              " bytes, expected " + std::to_string(nim->iname_offset + needed));
    }
  }
  if (nifti_image_load(nim.get()) < 0 || nim->data == nullptr) {
    return invalid_argument("NIfTI '" + path + "' is truncated or its voxel data is unreadable");
  }
  Image image{geometry, decode_voxels(static_cast<const char*>(nim->data), size_t(count), *type, false)};
  const double slope = nim->scl_slope;
  const double inter = nim->scl_inter;
  if (std::isfinite(slope) && slope != 0 && std::isfinite(inter) && !(slope == 1 && inter == 0)) {
    for (float& v : image.voxels) v = float(double(v) * slope + inter);
  }
  return image;
}

}  // namespace soiq
