#pragma once
// A floor for any exact scanline conversion of a mesh onto a grid, on one thread: what every such
// method does before it knows a single crossing, and the one write of its output.
//   1. one pass over the triangles, mapping each into the grid's index space (its three vertices,
//      through PhysicalToLattice: the map soiq uses) and finding its integer lattice range along
//      the two cross axes (the row lines it could cross: ceil of the smallest, floor of the largest
//      y and z, clamped to the grid);
//   2. write the dense uint8 mask once (allocated fresh, every byte stored).
// A method mapping each vertex once (shared by ~6 triangles) maps less than step 1; the floor
// follows the triangles, as a scanline method visits them.
// No edge test, no crossing, no sorting, no fill: the figure a conversion is measured against
// ("1d / floor" in BENCHMARKS.md). Compiled like soiq's kernels (cpu_dispatch.h), so both run at
// the same CPU level.
//
// Output   the mask (all zeros: the floor decides nothing) and, so that no step can be optimised
//          away, the number of lattice points in all the triangles' ranges.

#include <cstdint>

#include "core/base/image.h"
#include "core/base/image_geometry.h"
#include "core/base/triangle_mesh.h"

namespace soiq::bench {

struct FloorRun {
  Mask mask;
  int64_t lattice_points = 0;
};

FloorRun scanline_floor(const TriangleMesh& mesh, const ImageGeometry& geometry);

}  // namespace soiq::bench
