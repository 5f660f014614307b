#pragma once
// Validates the geometry of a legacy VTK polydata file (.vtk) and returns just that part, for
// vtkPolyDataReader to parse from memory. VTK 9.1's legacy reader crashes on truncated or
// corrupt files (it trusts every count), so it only ever sees sections checked here.
//
// Inputs   the file's bytes (ASCII or BINARY, file versions 3.0-5.1); `path` for messages.
// Output   the file up to its first attribute section (POINT_DATA, CELL_DATA, FIELD), which soiq
//          ignores anyway: header, DATASET POLYDATA, POINTS, VERTICES, LINES, POLYGONS,
//          TRIANGLE_STRIPS (legacy counts or 5.1 OFFSETS/CONNECTIVITY), without its METADATA
//          blocks (each up to the next blank line), so VTK never reads a byte not checked here.
// Errors   INVALID_ARGUMENT naming the file and the problem: not polydata, truncated section,
//          malformed count, cell point index out of range, METADATA without its ending blank line.
// Cost     O(file size); thread-safe.

#include <string>

#include "core/base/status.h"

namespace soiq {

Result<std::string> legacy_vtk_geometry(const std::string& bytes, const std::string& path);

}  // namespace soiq
