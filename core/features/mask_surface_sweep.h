#pragma once
// One pass over a structure's runs that gathers what the features of its marching-cubes surface
// (marching_cubes.h: iso 0.5, the mask padded by one voxel of zeros) need, without building that
// surface: how many cubes of each marching-cubes case there are and where (for the volume and area,
// mask_surface_shape.h), and, for every plane of constant i, j or k on the half-voxel lattice, the
// surface vertices' convex hull in that plane (for the 2D diameters, mask_maximum_2d_diameters.h,
// and to shortlist the 3D hull's vertices).
//
// Facts used: the marching-cubes vertices of a 0/1 mask are exactly the midpoints between an inside
// voxel centre and an outside 6-neighbour (each such edge is cut once at t = 1/2, and every cut edge
// of a cube carries a vertex of its triangles). In doubled index coordinates (X, Y, Z) = 2 (i, j, k)
// they are integers. Along a line of constant (j, k) the cube cases change only at run ends, so the
// sweep costs O(runs + lines), plus O(1) per vertex for the planes of constant i.
//
// Inputs   volume: runs on a valid grid (validate_geometry), run table matching it.
// Output   MaskSurfaceSweep below; `empty` when the volume has no voxel.
// Errors   INVALID_ARGUMENT  invalid geometry or run table.
// Cost     O(runs + lines + vertices) time; memory O(box faces): one entry per (plane, row) of each
//          plane family, i.e. about 4 (nx ny + ny nz + nz nx) for the structure's bounding box.
//          Thread-safe.

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "core/geometry/lattice_polygon.h"

namespace soiq {

// The vertices of one family of planes (constant X, Y or Z), by plane and row: in each plane the
// rows are the lines of constant `row axis`, and each row keeps its least and greatest coordinate
// along the `value axis` (only those can be hull vertices).
struct PlaneFamily {
  int axis = 0, row_axis = 0, value_axis = 0;  // 0 = X, 1 = Y, 2 = Z
  int64_t plane_base = 0, row_base = 0;        // doubled coordinate of plane 0 and row 0
  int64_t planes = 0, rows = 0;
  std::vector<int32_t> min, max;  // [plane * rows + row]; min > max for an empty row
  // Per plane, its hull (u = row coordinate, v = value coordinate, doubled, absolute).
  std::vector<std::vector<LatticePoint>> hulls;
  // [plane * rows + row]: bit 0 set iff the row's min is a hull vertex, bit 1 iff its max is.
  std::vector<uint8_t> on_hull;
  // True iff the vertex at doubled (plane, row, value) coordinates is one of its plane's hull vertices.
  bool is_hull_vertex(int64_t plane, int64_t row, int64_t value) const;
};

struct MaskSurfaceSweep {
  bool empty = true;
  std::array<int64_t, 3> lo{0, 0, 0}, hi{-1, -1, -1};  // inclusive voxel bounding box
  // Per marching-cubes case (cube_case_table.h numbering): cubes, and the sums of their lowest
  // corner's voxel index (i, j, k); a corner may be -1 (the padding).
  std::array<int64_t, 256> cube_count{};
  std::array<std::array<int64_t, 3>, 256> corner_sum{};
  // families[a]: the planes of constant doubled coordinate a (0: X, rows along Z, values Y;
  // 1: Y, rows along Z, values X; 2: Z, rows along Y, values X).
  std::array<PlaneFamily, 3> families;
};

Result<MaskSurfaceSweep> mask_surface_sweep(const RunLengthVolume& volume);

}  // namespace soiq
