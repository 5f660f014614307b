#pragma once
// A marching-cubes case table as data: for each of the 256 inside/outside patterns of a cube of
// 2 x 2 x 2 voxel centres, the triangles the surface at iso 0.5 has in that cube. It lets the
// mask-surface features be computed from runs (mask_surface_shape.h) with exactly the triangles
// of a given marching-cubes implementation, without building the mesh.
//
// Case index: bit (di + 2 dj + 4 dk) is set iff the voxel at offset (di, dj, dk) in {0,1}^3 from
// the cube's lowest corner is inside. Vertices are edge midpoints in doubled local coordinates
// (each in {0, 1, 2}: 2 * offset), triangles wound as the implementation winds them.

#include <array>
#include <cstdint>
#include <vector>

namespace soiq {

using CubeCaseTriangle = std::array<std::array<int8_t, 3>, 3>;  // 3 vertices x (x, y, z), doubled

struct CubeCaseTable {
  std::array<std::vector<CubeCaseTriangle>, 256> triangles;
};

}  // namespace soiq
