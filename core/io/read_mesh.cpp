#include "core/io/read_mesh.h"

#include "core/io/file_extension.h"
#include "core/io/parse_mesh.h"
#include "core/io/read_file_bytes.h"

namespace soiq {

Result<TriangleMesh> read_mesh(const std::string& path, bool ras) {
  const std::string ext = file_extension(path);
  if (ext != ".stl" && ext != ".obj" && ext != ".ply" && ext != ".off" && ext != ".vtk" && ext != ".vtp") {
    return invalid_argument("unknown mesh extension '" + ext + "' of '" + path +
                            "'; soiq reads .stl, .obj, .ply, .off, .vtk and .vtp");
  }
  SOIQ_ASSIGN_OR_RETURN(const std::string bytes, read_file_bytes(path, "mesh"));
  if (bytes.empty()) return invalid_argument("mesh file '" + path + "' is empty");
  return parse_mesh(bytes, ext, ras, path);
}

}  // namespace soiq
