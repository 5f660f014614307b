#pragma once
// Writes a surface model through VTK's writers, chosen by extension: .stl (binary), .obj, .ply
// (binary), .vtk (legacy), .vtp. Coordinates are written as stored (LPS mm).
// Errors: INVALID_ARGUMENT unknown extension; NOT_FOUND/INTERNAL when the file cannot be written.

#include <string>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Status write_mesh(const TriangleMesh& mesh, const std::string& path);

}  // namespace soiq
