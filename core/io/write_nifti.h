#pragma once
// Writes a 3D NIfTI-1 file (.nii, or gzip-compressed .nii.gz) through libnifti; the NIfTI branch
// of write_mask/write_image.
//
// Inputs   geometry (valid); type kUint8 or kFloat32; `voxels` holds geometry.voxel_count() of them.
// Output   qform (code 1, scanner) and sform (code 1) both set from the geometry, LPS converted to
//          NIfTI's RAS; pixdim = spacing; units mm. NIfTI-1 stores these as float32, so
//          read_nifti gives the geometry back to float precision (~1e-7 relative), not exactly.
// Errors   NOT_FOUND the directory does not exist; INTERNAL libnifti failed to write the file.
// Cost     O(voxels); thread-safe for distinct paths (see read_nifti.h on libnifti's globals).

#include <string>

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/io/voxel_type.h"

namespace soiq {

Status write_nifti(const ImageGeometry& geometry, VoxelType type, const void* voxels, const std::string& path);

}  // namespace soiq
