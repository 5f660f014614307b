#pragma once
// Parses a Wavefront OBJ surface held in memory, strictly, without VTK: hostile uploads never
// reach a third-party reader.
//
// Inputs   the file's bytes; `name` (file or upload name) for messages.
// Output   the `v` records as vertices (x y z, in file order) and the `f` records as triangles:
//          a polygon v1..vk becomes the fan (v1, vi, vi+1), orientation kept. Face corners may be
//          written v, v/vt, v//vn or v/vt/vn; indices are 1-based, or negative = relative to the
//          last record of that kind so far (-1 is the last vertex). Coordinates as written, as
//          doubles, no axis flip. May hold no triangles.
// Errors   INVALID_ARGUMENT "OBJ 'name' line N: ..." for: a number that is not whole and finite
//          ("'5abc' is not a number", "'nan' is not a finite number"); a `v` with fewer than 3 or
//          more than 7 values (x y z [w] or x y z r g b [a]); a face with fewer than 3 corners; an
//          index that is 0, malformed or out of range ("face index 7 is out of range (the file has
//          3 vertices)") — texture and normal indices are checked against their records too;
//          free-form geometry (curv, curv2, surf), which soiq cannot read.
// Cost     O(bytes) time, O(vertices + triangles) memory. Thread-safe.
// Caveats  vt, vn, vp are checked and dropped; l and p (lines, points) carry no surface and are
//          skipped; g, o, s, usemtl, mtllib and other records without geometry are ignored (an
//          mtllib file is never opened); `#` starts a comment. No line continuation ("\").
//          Non-convex polygons are fanned, not ear-cut (vtkOBJReader + vtkTriangleFilter ear-cut).

#include <string>
#include <string_view>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> parse_obj(std::string_view bytes, const std::string& name);

}  // namespace soiq
