#pragma once
// Parsing helpers shared by the `soiq` commands: one message style for every bad argument.

#include <string>

#include "core/status.h"
#include "core/vec3.h"

namespace soiq::cli {

// A finite number; INVALID_ARGUMENT "<what> must be a number, got '<text>'".
Result<double> parse_number(const std::string& text, const std::string& what);

// A whole number in [lo, hi].
Result<int> parse_int(const std::string& text, const std::string& what, int lo, int hi);

// "S" or "SX,SY,SZ" in mm, each > 0.
Result<Vec3> parse_spacing(const std::string& text);

// True when `path` ends with one of the mesh extensions soiq reads (.stl .obj .ply .vtk .vtp).
bool is_mesh_path(const std::string& path);

// True when `path` ends with `suffix`.
bool ends_with(const std::string& path, const std::string& suffix);

}  // namespace soiq::cli
