#pragma once
// The conversion methods soiq-bench times side by side, each prepared from a mesh and a grid so
// that only the conversion itself is timed: the mesh is already in the method's own input form
// (our TriangleMesh, a vtkPolyData, an itk::Mesh, a CGAL Surface_mesh and its AABB tree, OpenVDB's
// index-space point and triangle lists) and the returned closure builds the dense uint8
// mask on the grid, allocation included.

#include <functional>
#include <string>

#include "core/base/image.h"
#include "core/base/image_geometry.h"
#include "core/base/status.h"
#include "core/base/triangle_mesh.h"

namespace soiq::bench {

enum class Method {
  k1d,           // soiq::voxelize_1d (the production path)
  k2d,           // soiq::voxelize_2d_contours (the paper's 2D method)
  k3d,           // soiq::voxelize_3d_raycast (the paper's 3D method; the oracle)
  kVtkStencil,   // vtkPolyDataToImageStencil (tolerance 0), stencil extents into the mask
  kVtkEnclosed,  // vtkSelectEnclosedPoints over every voxel centre
  kItk,          // itk::TriangleMeshToBinaryImageFilter (when built with ITK)
  kCgal,         // CGAL::Side_of_triangle_mesh over every voxel centre (when built with CGAL)
  kOpenVdb,      // openvdb::tools::meshToVolume per connected surface, by parity (when built with OpenVDB)
};

// "1d", "2d", "3d", "vtk-stencil", "vtk-enclosed", "itk", "cgal", "openvdb".
const char* method_name(Method m);
// INVALID_ARGUMENT for an unknown name, or a peer's name ("itk", "cgal", "openvdb") in a build
// without that peer.
Result<Method> parse_method(const std::string& name);
bool method_available(Method m);

// One timed conversion: returns the dense mask on the grid.
using Conversion = std::function<Result<Mask>()>;

// Prepares `method` for `mesh` on `geometry` (untimed). `threads` applies to 1d (and to VTK's SMP
// back-end for vtk-enclosed, and to OpenVDB's TBB); the others are single-threaded.
Result<Conversion> prepare_conversion(Method method, const TriangleMesh& mesh, const ImageGeometry& geometry,
                                      int threads);

}  // namespace soiq::bench
