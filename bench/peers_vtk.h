#pragma once
// VTK as a benchmark peer (STYLE.md §7): the same mesh on the same grid through
// vtkPolyDataToImageStencil and vtkSelectEnclosedPoints.
//
// VTK images have no direction matrix. For an identity direction the mesh goes in as it is, with
// the grid's origin and spacing; otherwise it is first mapped (untimed) into the grid's frame
// index * spacing with origin 0, so VTK samples the same voxel centres.
//
// vtk-stencil  vtkPolyDataToImageStencil, tolerance 0 (no "near the surface" widening), output
//              extent = the grid; its inside sub-extents are written into the mask (timed).
// vtk-enclosed vtkSelectEnclosedPoints (default tolerance) over a point set of all voxel centres
//              built untimed; O(voxels x ray casts), meant for small grids. VTK's SMP back-end
//              runs it with its default thread count (vtkSMPTools.h does not compile as C++20 in
//              VTK 9.1, so `threads` cannot be passed on); pin the process to compare 1 thread.

#include "bench/conversion.h"

namespace soiq::bench {

Result<Conversion> prepare_vtk_stencil(const TriangleMesh& mesh, const ImageGeometry& geometry);
Result<Conversion> prepare_vtk_enclosed(const TriangleMesh& mesh, const ImageGeometry& geometry, int threads);

}  // namespace soiq::bench
