#pragma once
// The surface shape features (surface_shape.h) of a mask's marching-cubes surface, computed from
// its runs without building that surface (docs/DESIGN.md "Features": for a label map, the mesh features
// of the mask's marching-cubes surface at iso 0.5, as IBSI and PyRadiomics do).
//
// Inputs   sweep  mask_surface_sweep(volume) of the structure, not empty.
//          grid   the structure's grid (volume.geometry).
//          cases  the marching-cubes implementation's case table (marching_cubes_table() for
//                 soiq's marching_cubes).
// Output   the SurfaceShape surface_shape(marching_cubes(mask), grid.frame()) gives, to rounding
//          (on a sheared grid the cubes are parallelepipeds: areas through the direction matrix,
//          the box along the slices' frame from the hull shortlist, which holds its extremes):
//            volume  sum over cubes of the signed tetrahedra of their case's triangles: per case
//                    the triangles' determinants and area vectors are constants, and the cubes'
//                    positions enter through their corner sums (exact in integers; one rounding
//                    when scaled to mm3);
//            area    sum over cases of cube count x the case's area on this grid's spacing;
//            hull    the exact hull (convex_hull.h) of a shortlist of the vertices: a vertex of the 3D hull is a vertex
//            of
//                    the 2D hull of its plane of constant X, of constant Y and of constant Z, so
//                    only vertices on all three of those exact lattice hulls are passed;
//            diameter  point_set_diameter over the hull's vertices;
//            box     the vertices span (hi - lo + 1) voxels along each grid axis exactly.
// Errors   INVALID_ARGUMENT  an empty sweep.
// Cost     O(cases + planes x hull size) plus the hull of the shortlist (typically a few % of the
//          vertices). Thread-safe.

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/features/cube_case_table.h"
#include "core/features/mask_surface_sweep.h"
#include "core/features/surface_shape.h"

namespace soiq {

// `hull`: as surface_shape's (surface_shape.h): kSkip leaves the hull and diameter fields NaN.
Result<SurfaceShape> mask_surface_shape(const MaskSurfaceSweep& sweep, const ImageGeometry& grid,
                                        const CubeCaseTable& cases, HullPart hull = HullPart::kCompute);

}  // namespace soiq
