#pragma once
// Parses a surface model held in memory (an upload, or a file's bytes), the format named by the
// caller: stl, obj, ply and off by soiq's own strict parsers (parse_stl.h, parse_obj.h,
// parse_ply.h, parse_off.h; no third-party code sees the bytes), vtk (legacy polydata, VTK's reader
// behind a check of its counts) and vtp (VTK's XML parser, the arrays decoded by soiq)
// (parse_vtk_polydata.h).
//
// Inputs   bytes; `format` "stl", "obj", "ply", "off", "vtk" or "vtp" (any case, a leading dot
//          allowed: a file extension works); `ras` = true when the coordinates are RAS (3D
//          Slicer's older STL files, FreeSurfer): x and y are negated once so the mesh is LPS mm;
//          `name` (file or upload name) for messages.
// Output   the triangles of the file (polygons triangulated; lines and points dropped), vertices
//          as stored (in mm) but for the RAS flip.
// Errors   INVALID_ARGUMENT unknown format; empty bytes ("mesh 'name' is empty"); anything the
//          format's parser refuses (truncated, malformed, a number that is not whole and finite,
//          an index out of range — the message names `name`, and the line where there is one);
//          no triangles ("mesh 'name' contains no triangles"). RESOURCE_EXHAUSTED more than
//          2^31 vertices.
// Cost     O(bytes); thread-safe (no VTK PLY code, whose static state needed a lock).
// Caveats  No repair: defects are reported by mesh_defects(), not fixed here.

#include <string>
#include <string_view>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> parse_mesh(std::string_view bytes, const std::string& format, bool ras, const std::string& name);

}  // namespace soiq
