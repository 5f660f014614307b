#include "core/io/parse_mesh.h"

#include "core/io/header_text.h"
#include "core/io/parse_obj.h"
#include "core/io/parse_off.h"
#include "core/io/parse_ply.h"
#include "core/io/parse_stl.h"
#include "core/io/parse_vtk_polydata.h"

namespace soiq {
namespace {

Result<TriangleMesh> parse_format(std::string_view bytes, const std::string& format, const std::string& name) {
  if (format == "stl") return parse_stl(bytes, name);
  if (format == "obj") return parse_obj(bytes, name);
  if (format == "ply") return parse_ply(bytes, name);
  if (format == "off") return parse_off(bytes, name);
  if (format == "vtk") return parse_vtk_polydata(bytes, /*xml=*/false, name);
  return parse_vtk_polydata(bytes, /*xml=*/true, name);
}

}  // namespace

Result<TriangleMesh> parse_mesh(std::string_view bytes, const std::string& format, bool ras, const std::string& name) {
  std::string f = to_lower(format);
  if (!f.empty() && f[0] == '.') f.erase(0, 1);
  if (f != "stl" && f != "obj" && f != "ply" && f != "off" && f != "vtk" && f != "vtp") {
    return invalid_argument("unknown mesh format '" + format + "' of '" + name +
                            "'; soiq reads stl, obj, ply, off, vtk and vtp");
  }
  if (bytes.empty()) return invalid_argument("mesh '" + name + "' is empty");
  SOIQ_ASSIGN_OR_RETURN(TriangleMesh mesh, parse_format(bytes, f, name));
  if (mesh.triangles.empty()) return invalid_argument("mesh '" + name + "' contains no triangles");
  if (ras) {
    for (Vec3& p : mesh.vertices_mm) p = {-p[0], -p[1], p[2]};
  }
  return mesh;
}

}  // namespace soiq
