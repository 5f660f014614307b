#pragma once
// Writes a 3D NRRD file with attached gzip-encoded data; the .nrrd branch of write_mask/write_image.
//
// Inputs   geometry (valid); type kUint8 or kFloat32; `voxels` holds geometry.voxel_count() of them,
//          i fastest.
// Output   `space: left-posterior-superior`, `space directions` = D * diag(spacing) by column and
//          `space origin`, all printed with 17 significant digits so read_nrrd gives them back
//          exactly; `endian` of this machine.
// Errors   see write_file_bytes. Cost O(voxels); thread-safe for distinct paths.

#include <string>

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/io/voxel_type.h"

namespace soiq {

Status write_nrrd(const ImageGeometry& geometry, VoxelType type, const void* voxels, const std::string& path);

}  // namespace soiq
