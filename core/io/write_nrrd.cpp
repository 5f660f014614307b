#include "core/io/write_nrrd.h"

#include <bit>
#include <cstdio>
#include <string_view>

#include "core/io/write_file_bytes.h"
#include "core/io/zlib_codec.h"

namespace soiq {

Status write_nrrd(const ImageGeometry& g, VoxelType type, const void* voxels, const std::string& path) {
  if (type != VoxelType::kUint8 && type != VoxelType::kFloat32) {
    return internal_error("write_nrrd supports uint8 and float32 voxels only");
  }
  const size_t bytes = size_t(g.voxel_count()) * voxel_type_size(type);
  SOIQ_ASSIGN_OR_RETURN(const std::string data,
                        deflate_bytes(std::string_view(static_cast<const char*>(voxels), bytes), ZlibFormat::kGzip));
  std::string header = "NRRD0004\n# written by soiq\n";
  header += type == VoxelType::kUint8 ? "type: uint8\n" : "type: float\n";
  header += "dimension: 3\nspace: left-posterior-superior\n";
  char line[512];
  std::snprintf(line, sizeof line, "sizes: %lld %lld %lld\n", (long long)g.dims[0], (long long)g.dims[1],
                (long long)g.dims[2]);
  header += line;
  header += "space directions:";
  for (int c = 0; c < 3; ++c) {
    std::snprintf(line, sizeof line, " (%.17g,%.17g,%.17g)", g.direction[0][c] * g.spacing_mm[c],
                  g.direction[1][c] * g.spacing_mm[c], g.direction[2][c] * g.spacing_mm[c]);
    header += line;
  }
  header += "\nkinds: domain domain domain\n";
  header += std::endian::native == std::endian::big ? "endian: big\n" : "endian: little\n";
  header += "encoding: gzip\n";
  std::snprintf(line, sizeof line, "space origin: (%.17g,%.17g,%.17g)\n\n", g.origin_mm[0], g.origin_mm[1],
                g.origin_mm[2]);
  header += line;
  return write_file_bytes(path, header + data, "NRRD image");
}

}  // namespace soiq
