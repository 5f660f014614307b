#pragma once
// Checks that a PLY file is structurally whole before vtkPLYReader sees it: vtkPLYReader (VTK 9.1)
// frees an invalid pointer and aborts the process on a truncated header, and reads past the end of
// truncated data. This walks the header and every element, property and list of the body.
//
// Inputs   the file's bytes; `path` for messages.
// Output   OK when the header is well formed (ply, format ascii/binary_little_endian/
//          binary_big_endian 1.0, element/property lines of known types, end_header), the
//          `vertex` element has x, y and z, the body holds every value the header announces, and
//          every face vertex index names a vertex (vtkPLYReader would read out of bounds).
// Errors   INVALID_ARGUMENT naming the file and the first problem (e.g. "truncated").
// Cost     O(file size); thread-safe.

#include <string>

#include "core/status.h"

namespace soiq {

Status check_ply_structure(const std::string& bytes, const std::string& path);

}  // namespace soiq
