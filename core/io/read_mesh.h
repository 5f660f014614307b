#pragma once
// Reads a surface model file, the format chosen by its extension: .stl (ASCII or binary), .obj,
// .ply, .off (soiq's own strict parsers), .vtk (legacy polydata, VTK's reader behind a check),
// .vtp (VTK's XML parser, arrays decoded by soiq). The file's bytes go to parse_mesh (parse_mesh.h),
// which uploads use too.
//
// Inputs   path; `ras` = true when the file's coordinates are RAS (3D Slicer's older STL files,
//          FreeSurfer): x and y are negated once so the mesh is LPS mm.
// Output   the triangles of the file (polygons with more than 3 vertices are triangulated;
//          lines and points are ignored), vertices as stored.
// Errors   NOT_FOUND the file does not exist or cannot be opened;
//          INVALID_ARGUMENT unknown extension, empty, truncated or malformed file, no triangles,
//          face indices out of range — the message names the file and the problem;
//          RESOURCE_EXHAUSTED the file is larger than 4 GiB or has more than 2^31 vertices.
// Cost     O(file size) time and memory (the whole file is read first). Thread-safe.
// Caveats  No repair: defects are reported by mesh_defects(), not fixed here.

#include <string>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> read_mesh(const std::string& path, bool ras = false);

}  // namespace soiq
