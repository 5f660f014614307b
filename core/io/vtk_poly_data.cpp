#include "core/io/vtk_poly_data.h"

#include <vtkCellArray.h>
#include <vtkNew.h>
#include <vtkPoints.h>

namespace soiq {

vtkSmartPointer<vtkPolyData> to_vtk_poly_data(const TriangleMesh& mesh) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();  // keep LPS coordinates exact where the format stores doubles
  points->SetNumberOfPoints(vtkIdType(mesh.vertices_mm.size()));
  for (size_t i = 0; i < mesh.vertices_mm.size(); ++i) points->SetPoint(vtkIdType(i), mesh.vertices_mm[i].data());
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(vtkIdType(mesh.triangles.size()), vtkIdType(3 * mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    polys->InsertNextCell(3, ids);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  return poly;
}

}  // namespace soiq
