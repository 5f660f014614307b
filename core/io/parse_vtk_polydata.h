#pragma once
// Parses a VTK polydata surface held in memory: legacy .vtk through VTK's reader, after
// legacy_vtk_geometry has checked it and cut it to its geometry; XML .vtp through VTK's XML parser
// with the arrays decoded and checked by soiq (vtk_xml_polydata.h). No temporary file is written.
//
// Inputs   the file's bytes; `xml` = true for .vtp, false for legacy .vtk; `name` for messages.
// Output   the triangles of the file (polygons and strips triangulated by vtkTriangleFilter, ear
//          cutting; lines and points dropped), vertices as stored, no axis flip. May hold no
//          triangles.
// Errors   INVALID_ARGUMENT malformed or truncated file, cell point index out of range, with VTK's
//          own words when it gives some; RESOURCE_EXHAUSTED more than 2^31 points, or a .vtp whose
//          compressed arrays declare more than 64 times its size.
// Cost     O(bytes + decoded size) plus VTK's copies of the input. Thread-safe.

#include <string>
#include <string_view>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> parse_vtk_polydata(std::string_view bytes, bool xml, const std::string& name);

}  // namespace soiq
