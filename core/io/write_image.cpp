#include "core/io/write_image.h"

#include "core/io/file_extension.h"
#include "core/io/voxel_type.h"
#include "core/io/write_metaimage.h"
#include "core/io/write_nifti.h"
#include "core/io/write_nrrd.h"

namespace soiq {
namespace {

Status write_voxels(const ImageGeometry& g, VoxelType type, const void* voxels, size_t count, const std::string& path) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(g));
  SOIQ_RETURN_IF_ERROR(check_evenly_spaced(g, "'" + path + "'"));
  if (count != size_t(g.voxel_count())) {
    return invalid_argument("cannot write '" + path + "': " + std::to_string(count) + " voxels for a grid of " +
                            describe(g));
  }
  const std::string ext = file_extension(path);
  if (ext == ".nii" || ext == ".nii.gz") return write_nifti(g, type, voxels, path);
  if (ext == ".nrrd") return write_nrrd(g, type, voxels, path);
  if (ext == ".mha") return write_metaimage(g, type, voxels, path);
  return invalid_argument("unknown image extension '" + ext + "' of '" + path +
                          "'; soiq writes .nii, .nii.gz, .nrrd and .mha");
}

}  // namespace

Status check_evenly_spaced(const ImageGeometry& g, const std::string& what) {
  if (!g.uneven()) return ok_status();
  return failed_precondition("cannot write " + what +
                             ": NIfTI, NRRD and MetaImage hold evenly spaced slices only, and " + describe(g) +
                             "; export a DICOM SEG (soiq export-seg), which keeps each slice's position, or convert "
                             "onto a grid of your own (--spacing)");
}

Status write_mask(const Mask& mask, const std::string& path) {
  return write_voxels(mask.geometry, VoxelType::kUint8, mask.voxels.data(), mask.voxels.size(), path);
}

Status write_image(const Image& image, const std::string& path) {
  return write_voxels(image.geometry, VoxelType::kFloat32, image.voxels.data(), image.voxels.size(), path);
}

}  // namespace soiq
