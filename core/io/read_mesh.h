#pragma once
// Reads a surface model through VTK's readers, chosen by file extension:
// .stl (ASCII or binary), .obj, .ply, .vtk (legacy polydata), .vtp.
//
// Inputs   path; `ras` = true when the file's coordinates are RAS (3D Slicer's older STL files,
//          FreeSurfer): x and y are negated once so the mesh is LPS mm.
// Output   the triangles of the file (polygons with more than 3 vertices are triangulated;
//          lines and points are ignored), vertices as stored.
// Errors   NOT_FOUND the file does not exist or cannot be opened;
//          INVALID_ARGUMENT unknown extension, empty, truncated or malformed file, no triangles,
//          face indices out of range — the message names the file and the problem.
// Caveats  No repair: defects are reported by mesh_defects(), not fixed here.

#include <string>

#include "core/status.h"
#include "core/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> read_mesh(const std::string& path, bool ras = false);

}  // namespace soiq
