#include "server/app/uploaded_files.h"

#include <algorithm>
#include <array>

#include "core/io/parse_mesh.h"
#include "core/io/read_image.h"
#include "core/io/write_mesh.h"
#include "server/util/temp_file.h"

namespace soiq::server {
namespace {

Result<std::string> checked_format(const std::string& format, const std::vector<std::string>& known, const char* what) {
  std::string f = format;
  std::transform(f.begin(), f.end(), f.begin(), [](unsigned char c) { return std::tolower(c); });
  if (!f.empty() && f[0] == '.') f.erase(0, 1);
  if (std::find(known.begin(), known.end(), f) != known.end()) return f;
  std::string list;
  for (const auto& k : known) list += (list.empty() ? "" : ", ") + k;
  return invalid_argument(std::string("unknown ") + what + " format '" + format + "'; known: " + list);
}

const std::vector<std::string> kMeshFormats = {"stl", "obj", "ply", "off", "vtk", "vtp"};
const std::vector<std::string> kMeshDownloadFormats = {"stl", "obj", "ply", "vtk", "vtp"};

}  // namespace

Result<ParsedSurface> parse_surface(const std::string& bytes, const std::string& format, bool ras, bool robust,
                                    const std::string& name) {
  SOIQ_ASSIGN_OR_RETURN(const std::string f, checked_format(format, kMeshFormats, "mesh"));
  if (bytes.empty()) return invalid_argument("surface '" + name + "' is empty (0 bytes uploaded)");
  SOIQ_ASSIGN_OR_RETURN(TriangleMesh mesh, parse_mesh(bytes, f, ras, name));
  ParsedSurface out{std::move(mesh), {}};
  out.defects = mesh_defects(out.mesh);
  SOIQ_RETURN_IF_ERROR(validate_mesh(out.mesh, out.defects, name));
  if (!out.defects.closed()) {
    if (!robust)
      return failed_precondition("surface '" + name + "' is not closed (" + describe(out.defects) +
                                 "): repair it, or upload it in robust mode (--robust) to convert it by the "
                                 "three-axis vote");
  } else {
    orient_outward(out.mesh);
  }
  return out;
}

Result<Image> parse_image(const std::string& bytes, const std::string& format, const std::string& name,
                          const ImageDecodeLimits& limits) {
  SOIQ_ASSIGN_OR_RETURN(const std::string f, checked_format(format, {"nii", "nii.gz", "nrrd", "mha"}, "image"));
  if (bytes.empty()) return invalid_argument("image '" + name + "' is empty (0 bytes uploaded)");
  return decode_image(bytes, f, name, limits);
}

Result<std::string> surface_bytes(const TriangleMesh& mesh, const std::string& format, bool ras) {
  SOIQ_ASSIGN_OR_RETURN(const std::string f,
                        checked_format(format.empty() ? "stl" : format, kMeshDownloadFormats, "mesh"));
  SOIQ_ASSIGN_OR_RETURN(TempFile file, TempFile::create("." + f));
  if (ras) {
    TriangleMesh flipped = mesh;
    for (Vec3& p : flipped.vertices_mm) p = {-p[0], -p[1], p[2]};
    SOIQ_RETURN_IF_ERROR(write_mesh(flipped, file.path()));
  } else {
    SOIQ_RETURN_IF_ERROR(write_mesh(mesh, file.path()));
  }
  return file.read();
}

}  // namespace soiq::server
