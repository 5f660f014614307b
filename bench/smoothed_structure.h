#pragma once
// A "real-looking" surface for the benchmarks: a real segmentation's marching-cubes surface,
// smoothed and refined the way viewers and segmentation tools export structures (3D Slicer's
// surface smoothing is VTK's windowed-sinc filter), so its vertices lie in general position on a
// smooth, lumpy shape rather than on the half-voxel lattice of the simulated models.
//
// Inputs   mask            a real structure's mask (non-empty).
//          min_triangles   Loop subdivision steps (each x4 triangles) are added until the surface has
//                          at least this many triangles.
// Output   a closed, outward-facing triangle mesh in the mask's LPS mm frame.
// Method   our marching_cubes, then vtkWindowedSincPolyDataFilter (20 iterations, pass band 0.05,
//          normalised coordinates, boundary and feature edges left free), then
//          vtkLoopSubdivisionFilter. Deterministic.
// Errors   INVALID_ARGUMENT for an empty mask; INTERNAL if VTK returns no triangles.

#include <cstddef>

#include "core/base/image.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq::bench {

Result<TriangleMesh> smoothed_structure(const Mask& mask, size_t min_triangles);

}  // namespace soiq::bench
