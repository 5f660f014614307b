#include "bench/smoothed_structure.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkLoopSubdivisionFilter.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include "core/io/marching_cubes.h"
#include "core/io/vtk_poly_data.h"

namespace soiq::bench {

namespace {

Result<TriangleMesh> from_polydata(vtkPolyData* poly) {
  TriangleMesh mesh;
  mesh.vertices_mm.resize(size_t(poly->GetNumberOfPoints()));
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) poly->GetPoint(i, mesh.vertices_mm[size_t(i)].data());
  auto ids = vtkSmartPointer<vtkIdList>::New();
  vtkCellArray* polys = poly->GetPolys();
  polys->InitTraversal();
  while (polys->GetNextCell(ids)) {
    if (ids->GetNumberOfIds() != 3) return internal_error("smoothed structure: VTK returned a non-triangle cell");
    mesh.triangles.push_back({int32_t(ids->GetId(0)), int32_t(ids->GetId(1)), int32_t(ids->GetId(2))});
  }
  if (mesh.triangles.empty()) return internal_error("smoothed structure: VTK returned no triangles");
  return mesh;
}

}  // namespace

Result<TriangleMesh> smoothed_structure(const Mask& mask, size_t min_triangles) {
  SOIQ_ASSIGN_OR_RETURN(const TriangleMesh surface, marching_cubes(mask));
  if (surface.triangles.empty()) return invalid_argument("smoothed structure: the mask is empty");
  auto smooth = vtkSmartPointer<vtkWindowedSincPolyDataFilter>::New();
  smooth->SetInputData(to_vtk_poly_data(surface));
  smooth->SetNumberOfIterations(20);
  smooth->SetPassBand(0.05);
  smooth->NormalizeCoordinatesOn();
  smooth->BoundarySmoothingOn();
  smooth->FeatureEdgeSmoothingOff();
  smooth->NonManifoldSmoothingOn();
  smooth->Update();
  vtkSmartPointer<vtkPolyData> poly = smooth->GetOutput();
  int steps = 0;
  for (size_t n = surface.triangles.size(); n < min_triangles; n *= 4) ++steps;
  if (steps > 0) {
    auto refine = vtkSmartPointer<vtkLoopSubdivisionFilter>::New();
    refine->SetInputData(poly);
    refine->SetNumberOfSubdivisions(steps);
    refine->Update();
    poly = refine->GetOutput();
  }
  return from_polydata(poly);
}

}  // namespace soiq::bench
