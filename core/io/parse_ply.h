#pragma once
// Parses a PLY surface (ascii, binary_little_endian or binary_big_endian 1.0) held in memory,
// strictly, without VTK: vtkPLYReader crashed the server on a vertex line with too few values.
//
// Inputs   the file's bytes; `name` (file or upload name) for messages.
// Output   the `vertex` element's x, y, z (any scalar type, widened to double exactly) as vertices
//          in file order, and the `face` element's `vertex_indices` (or `vertex_index`) lists as
//          triangles: a polygon v1..vk becomes the fan (v1, vi, vi+1), orientation kept. Every other
//          property and element is read past by its declared type and size. No axis flip. May hold
//          no triangles (no face element).
// Errors   INVALID_ARGUMENT naming `name` and the first problem: bad magic, format or header line;
//          no vertex element with scalar x, y and z; an element count the remaining bytes cannot
//          hold (checked before anything is allocated, so "element vertex 1000000000000" in a
//          1 KB file fails at once); ASCII: one element per line, "PLY 'name' line N: vertex has 2
//          values, the header declares 3", a value that is not a whole number of its type
//          ("'5abc' is not a number", "'1.5' is not an integer", "300 is out of range for uchar"),
//          a NaN or infinite coordinate; binary: truncated data, bytes after the last element,
//          a non-finite coordinate; a face with fewer than 3 corners or a corner index outside
//          [0, vertex count); a list count that is negative.
// Cost     O(bytes) time, O(vertices + triangles) memory. Thread-safe (no global state, unlike
//          vtkPLY).
// Caveats  Non-convex polygons are fanned, not ear-cut. Values of skipped properties must be
//          numbers of their type but may be NaN. Only format version 1.0.

#include <string>
#include <string_view>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> parse_ply(std::string_view bytes, const std::string& name);

}  // namespace soiq
