#pragma once
// Writes a 3D MetaImage (.mha) with zlib-compressed LOCAL data; the .mha branch of
// write_mask/write_image.
//
// Inputs   geometry (valid); type kUint8 or kFloat32; `voxels` holds geometry.voxel_count() of them.
// Output   Offset = origin, ElementSpacing, TransformMatrix = the direction's columns one after the
//          other (ITK's order, see read_metaimage.h), 17 significant digits so read_metaimage
//          gives them back exactly; byte order of this machine.
// Errors   see write_file_bytes. Cost O(voxels); thread-safe for distinct paths.

#include <string>

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/io/voxel_type.h"

namespace soiq {

Status write_metaimage(const ImageGeometry& geometry, VoxelType type, const void* voxels, const std::string& path);

}  // namespace soiq
