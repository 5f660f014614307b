#include "core/io/write_nifti.h"

#include <nifti2_io.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <system_error>

#include "core/io/file_extension.h"
#include "core/io/header_text.h"
#include "core/io/write_file_bytes.h"

namespace soiq {
namespace {

struct NiftiFree {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};

}  // namespace

Status write_nifti(const ImageGeometry& g, VoxelType type, const void* voxels, const std::string& path) {
  if (type != VoxelType::kUint8 && type != VoxelType::kFloat32) {
    return internal_error("write_nifti supports uint8 and float32 voxels only");
  }
  static std::once_flag quiet;
  std::call_once(quiet, [] { nifti_set_debug_level(0); });
  const std::string dir = directory_of(path);
  std::error_code ec;
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec)) return write_error(path, ENOENT, "NIfTI image");

  const int64_t dims[8] = {3, g.dims[0], g.dims[1], g.dims[2], 1, 1, 1, 1};
  std::unique_ptr<nifti_image, NiftiFree> nim(
      nifti_make_new_nim(dims, type == VoxelType::kUint8 ? DT_UINT8 : DT_FLOAT32, /*data_fill=*/0));
  if (!nim) return internal_error("libnifti could not create an image header for '" + path + "'");
  const size_t bytes = size_t(g.voxel_count()) * voxel_type_size(type);
  nim->data = std::malloc(bytes > 0 ? bytes : 1);  // nifti_image_free releases it with free()
  if (!nim->data) return resource_exhausted("out of memory writing '" + path + "'");
  if (bytes > 0) std::memcpy(nim->data, voxels, bytes);

  // The RAS affine: diag(-1,-1,1) * [D diag(spacing) | origin].
  nifti_dmat44 affine{};
  for (int r = 0; r < 3; ++r) {
    const double flip = r < 2 ? -1.0 : 1.0;
    for (int c = 0; c < 3; ++c) affine.m[r][c] = flip * g.direction[r][c] * g.spacing_mm[c];
    affine.m[r][3] = flip * g.origin_mm[r];
  }
  affine.m[3][3] = 1.0;
  nim->sform_code = NIFTI_XFORM_SCANNER_ANAT;
  nim->sto_xyz = affine;
  double dx = 0, dy = 0, dz = 0, qfac = 1;
  nifti_dmat44_to_quatern(affine, &nim->quatern_b, &nim->quatern_c, &nim->quatern_d, &nim->qoffset_x, &nim->qoffset_y,
                          &nim->qoffset_z, &dx, &dy, &dz, &qfac);
  // A quaternion holds a rotation only: a sheared (tilted) grid is in the sform alone, and readers
  // told the qform is unknown take the sform.
  nim->qform_code = g.sheared() ? NIFTI_XFORM_UNKNOWN : NIFTI_XFORM_SCANNER_ANAT;
  nim->qfac = qfac;
  nim->dx = nim->pixdim[1] = g.spacing_mm[0];
  nim->dy = nim->pixdim[2] = g.spacing_mm[1];
  nim->dz = nim->pixdim[3] = g.spacing_mm[2];
  nim->pixdim[0] = qfac;
  nim->qto_xyz = nifti_quatern_to_dmat44(nim->quatern_b, nim->quatern_c, nim->quatern_d, nim->qoffset_x, nim->qoffset_y,
                                         nim->qoffset_z, nim->dx, nim->dy, nim->dz, qfac);
  nim->xyz_units = NIFTI_UNITS_MM;
  nim->nifti_type = NIFTI_FTYPE_NIFTI1_1;

  // Write beside the target under a temporary name with the same extension, then rename, so a
  // crash never leaves a half-written image under the real name.
  const std::string name = path.substr(dir.size());
  const std::string tmp = dir + ".tmp" + std::to_string(::getpid()) + "-" + name;
  if (nifti_set_filenames(nim.get(), tmp.c_str(), 0, 1) != 0) {
    return internal_error("libnifti rejected the file name '" + path + "'");
  }
  nifti_image_write(nim.get());
  // nifti_image_write reports nothing: check that a plausible file appeared.
  const auto written = std::filesystem::file_size(tmp, ec);
  const bool plain = file_extension(path) == ".nii";
  if (ec || written == 0 || (plain && written < 352 + bytes)) {
    std::remove(tmp.c_str());
    return internal_error("libnifti failed to write '" + path + "' (disk full or not writable?)");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::remove(tmp.c_str());
    return write_error(path, err, "NIfTI image");
  }
  return ok_status();
}

}  // namespace soiq
