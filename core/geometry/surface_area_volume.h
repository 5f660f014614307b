#pragma once
// The area and the enclosed volume of a closed triangle mesh, in one pass over its triangles: the
// measures behind every surface feature (docs/DESIGN.md "Features"; IBSI C0JK mesh volume, C0JK/surface
// area), shared by surface_shape and by the service's hull-free path so that both give the same
// doubles, bit for bit.
//
// Inputs   mesh: LPS mm, closed and outward-facing for a meaningful volume.
// Output   area_mm2   sum over triangles of |n| / 2, n = (b - a) x (c - a);
//          volume_mm3 sum over triangles of (a - o) . n / 6, o the mesh's first vertex (the
//                     signed tetrahedra against o: the same volume as against the origin for a
//                     closed surface, with less cancellation far from it);
//          used       per vertex, 1 iff some triangle uses it.
// Errors   INVALID_ARGUMENT  no triangles; a vertex index out of range; a used vertex with a
//                            non-finite coordinate; volume <= 0 (an inward-facing or open
//                            surface: use orient_outward or repair it).
// Cost     O(T + V), one pass over the triangles. Thread-safe.

#include <cstdint>
#include <vector>

#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

struct SurfaceAreaVolume {
  double area_mm2 = 0;
  double volume_mm3 = 0;
  std::vector<uint8_t> used;
};

Result<SurfaceAreaVolume> surface_area_volume(const TriangleMesh& mesh);

}  // namespace soiq
