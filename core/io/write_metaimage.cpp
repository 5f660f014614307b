#include "core/io/write_metaimage.h"

#include <bit>
#include <cstdio>
#include <string_view>

#include "core/io/write_file_bytes.h"
#include "core/io/zlib_codec.h"

namespace soiq {

Status write_metaimage(const ImageGeometry& g, VoxelType type, const void* voxels, const std::string& path) {
  if (type != VoxelType::kUint8 && type != VoxelType::kFloat32) {
    return internal_error("write_metaimage supports uint8 and float32 voxels only");
  }
  const size_t bytes = size_t(g.voxel_count()) * voxel_type_size(type);
  SOIQ_ASSIGN_OR_RETURN(const std::string data,
                        deflate_bytes(std::string_view(static_cast<const char*>(voxels), bytes), ZlibFormat::kZlib));
  const Mat3& d = g.direction;
  char text[2048];
  std::snprintf(text, sizeof text,
                "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = %s\n"
                "CompressedData = True\nCompressedDataSize = %zu\n"
                "TransformMatrix = %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n"
                "Offset = %.17g %.17g %.17g\nCenterOfRotation = 0 0 0\n"
                "ElementSpacing = %.17g %.17g %.17g\nDimSize = %lld %lld %lld\n"
                "ElementType = %s\nElementDataFile = LOCAL\n",
                std::endian::native == std::endian::big ? "True" : "False", data.size(), d[0][0], d[1][0], d[2][0],
                d[0][1], d[1][1], d[2][1], d[0][2], d[1][2], d[2][2], g.origin_mm[0], g.origin_mm[1], g.origin_mm[2],
                g.spacing_mm[0], g.spacing_mm[1], g.spacing_mm[2], (long long)g.dims[0], (long long)g.dims[1],
                (long long)g.dims[2], type == VoxelType::kUint8 ? "MET_UCHAR" : "MET_FLOAT");
  return write_file_bytes(path, std::string(text) + data, "MetaImage");
}

}  // namespace soiq
