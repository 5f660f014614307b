#pragma once
// Uploaded bytes -> core objects, and core objects -> bytes for download, through the same
// readers and writers as the offline CLI (core/io), so an upload is checked exactly as a local
// file would be.
//
// parse_surface: `format` is stl, obj, ply, off, vtk or vtp, parsed in memory (core/io
// parse_mesh: no third-party reader sees the simple formats); `ras` flips x and y into LPS. The mesh is
// validated (no triangles, NaN vertices, bad indices: INVALID_ARGUMENT naming `name`), and a closed
// mesh is turned to face outward. An open or inconsistently oriented surface is FAILED_PRECONDITION
// unless `robust` (its conversions then use the three-axis vote).
// parse_image: `format` is nii, nii.gz, nrrd or mha, parsed in memory (core/io decode_image): a
// header naming a separate data file is refused, so no upload makes soiqd read a server file;
// INVALID_ARGUMENT for a malformed file.
// surface_bytes: the mesh in `format` (stl default), flipped to RAS when asked.

#include <string>

#include "core/base/image.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"
#include "core/geometry/mesh_defects.h"
#include "core/io/image_decode_limits.h"

namespace soiq::server {

struct ParsedSurface {
  TriangleMesh mesh;
  MeshDefects defects;
};

Result<ParsedSurface> parse_surface(const std::string& bytes, const std::string& format, bool ras, bool robust,
                                    const std::string& name);
Result<Image> parse_image(const std::string& bytes, const std::string& format, const std::string& name,
                          const ImageDecodeLimits& limits);
Result<std::string> surface_bytes(const TriangleMesh& mesh, const std::string& format, bool ras);

}  // namespace soiq::server
