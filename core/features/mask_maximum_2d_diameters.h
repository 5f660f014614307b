#pragma once
// The maximum 2D diameters (maximum_2d_diameters.h) of a mask's marching-cubes surface, from the
// per-plane lattice hulls of mask_surface_sweep instead of the surface's vertices: the same planes
// (constant k, j, i, half-voxel planes included), the same vertices (those hulls' vertices are the
// extreme vertices of each plane), distances in mm from the grid's spacing (and, on a sheared
// grid, its direction: the planes holding the leaning k axis are not at right angles).
//
// Inputs   sweep  mask_surface_sweep(volume), not empty; grid  the mask's grid.
// Output   maximum_2d_diameters(marching_cubes(mask), grid) to rounding: per plane the largest
//          distance between two hull vertices (rotating calipers, lattice_polygon.h), max over planes.
// Errors   INVALID_ARGUMENT  an empty sweep.
// Cost     O(total hull vertices). Thread-safe.

#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/vec3.h"
#include "core/features/mask_surface_sweep.h"
#include "core/features/maximum_2d_diameters.h"

namespace soiq {

Result<Maximum2DDiameters> mask_maximum_2d_diameters(const MaskSurfaceSweep& sweep, const ImageGeometry& grid);

}  // namespace soiq
