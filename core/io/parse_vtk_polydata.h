#pragma once
// Parses a VTK polydata surface held in memory through VTK's own readers: legacy .vtk (after
// legacy_vtk_geometry has checked it and cut it to its geometry) or XML .vtp. Both readers read
// from a string, so no temporary file is written.
//
// Inputs   the file's bytes; `xml` = true for .vtp, false for legacy .vtk; `name` for messages.
// Output   the triangles of the file (polygons and strips triangulated by vtkTriangleFilter, ear
//          cutting; lines and points dropped), vertices as stored, no axis flip. May hold no
//          triangles.
// Errors   INVALID_ARGUMENT malformed or truncated file, cell point index out of range, with VTK's
//          own words when it gives some; RESOURCE_EXHAUSTED more than 2^31 points.
// Cost     O(bytes) plus VTK's copies of the input (the .vtp string is copied once). Thread-safe.

#include <string>
#include <string_view>

#include "core/status.h"
#include "core/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> parse_vtk_polydata(std::string_view bytes, bool xml, const std::string& name);

}  // namespace soiq
