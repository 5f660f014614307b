#pragma once
// Parses an OFF (Object File Format, Geomview) surface held in memory, strictly, without VTK.
//
// Inputs   the file's bytes; `name` (file or upload name) for messages.
// Output   "OFF", then "nv nf ne" (on the OFF line or the next), nv lines "x y z" and nf lines
//          "k i1 .. ik [r g b [a]]": the vertices in file order and each face as the fan
//          (i1, ij, ij+1), orientation kept. Indices are 0-based. `#` starts a comment. No axis
//          flip. May hold no triangles.
// Errors   INVALID_ARGUMENT "OFF 'name' line N: ..." for a missing "OFF" keyword; counts the
//          remaining bytes cannot hold (checked before allocating); a value that is not a whole
//          finite number; a vertex line without exactly 3 values; a face with fewer than 3 corners,
//          a wrong number of values or an index outside [0, nv); data after the last face; a
//          truncated file.
// Cost     O(bytes) time, O(vertices + triangles) memory. Thread-safe.
// Caveats  Only plain "OFF": the COFF, NOFF, STOFF, 4OFF, nOFF variants and binary OFF are
//          refused. Non-convex faces are fanned, not ear-cut.

#include <string>
#include <string_view>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> parse_off(std::string_view bytes, const std::string& name);

}  // namespace soiq
