#pragma once
// The largest vertex-to-vertex distance of a surface within each plane of constant k, j and i of
// its grid (docs/DESIGN.md "Features": maximum_2d_diameter_slice_mm / _column_mm / _row_mm;
// PyRadiomics Maximum2DDiameterSlice / Column / Row).
//
// Inputs   mesh  vertices in LPS mm; in practice marching_cubes(mask) of a mask on `grid`, whose
//                vertices sit on integer or half-integer continuous-index planes.
//          grid  the grid the mesh belongs to (validate_geometry must pass).
// Output   slice_mm   max distance between two vertices with the same k (axial for DICOM axial
//                     series), column_mm the same for j, row_mm for i. Vertices are grouped by
//                     their continuous-index coordinate rounded to the nearest multiple of 1/2,
//                     so half-voxel planes (the edge midpoints between two slices) form groups of
//                     their own, exactly as PyRadiomics' exact-coordinate grouping does for a
//                     marching-cubes mesh. A plane with a single vertex contributes 0.
// Method   per axis: sort the vertices by (plane, u, v) with (u, v) the in-plane coordinates in mm,
//          Andrew's monotone chain gives each plane's 2D convex hull, and the largest distance
//          between two hull vertices is the plane's diameter.
// Errors   INVALID_ARGUMENT  invalid grid, empty mesh, non-finite vertex.
// Cost     O(V log V) time, O(V) memory, plus O(h^2) per plane for h hull vertices. Thread-safe.
// Caveats  For a surface whose vertices are not on the half-index lattice (a stored surface
//          model), each group is the slab of vertices within 1/4 voxel of a half-index plane, so
//          the values are only indicative; use the marching-cubes mesh for PyRadiomics' values.

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq {

struct Maximum2DDiameters {
  double slice_mm = 0;   // planes of constant k
  double column_mm = 0;  // planes of constant j
  double row_mm = 0;     // planes of constant i
};

Result<Maximum2DDiameters> maximum_2d_diameters(const TriangleMesh& mesh, const ImageGeometry& grid);

}  // namespace soiq
