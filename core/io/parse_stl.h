#pragma once
// Parses an STL surface (ASCII or binary) held in memory, strictly, without VTK: hostile uploads
// never reach a third-party reader.
//
// Inputs   the file's bytes; `name` (file or upload name) for messages.
// Output   the facets as an indexed mesh: exactly equal corners share one vertex (-0 equals +0),
//          vertices in first-seen order, facets in file order. A facet whose corners are not three
//          distinct vertices after merging is dropped, as vtkSTLReader's merging did, so read
//          results stay the same. Coordinates as stored (binary: float32 widened exactly; ASCII:
//          the written decimal as a double), no axis flip. May hold no triangles.
// Errors   INVALID_ARGUMENT naming `name` and the problem:
//          - binary (exactly 84 + 50 n bytes, n the count at byte 80): "truncated: 50 bytes, less
//            than the 84-byte header", "its header announces 2 triangles (184 bytes) but the file
//            has 164 bytes", a NaN or infinite vertex coordinate (facet k);
//          - ASCII ("solid" first): the grammar solid / facet normal x y z / outer loop / vertex
//            x y z (three times) / endloop / endfacet / endsolid, one keyword line at a time
//            (keywords in any case, several solids allowed); "line N: expected 'endloop', found
//            'vertex'"; a coordinate that is not a whole finite number ("'5abc' is not a number").
// Cost     O(bytes) time, O(facets) memory; allocation only after the size is checked. Thread-safe.
// Caveats  Normals and the binary attribute bytes are ignored (normals may be NaN: some exporters
//          write NaN normals on degenerate facets). VTK's ASCII "color" extension is refused.

#include <string>
#include <string_view>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

Result<TriangleMesh> parse_stl(std::string_view bytes, const std::string& name);

}  // namespace soiq
