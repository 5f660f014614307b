#include "core/io/marching_cubes_cases.h"

#include <vtkCellArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <cassert>
#include <cmath>

#include "core/io/vtk_messages.h"

namespace soiq {
namespace {

// The triangles of every cube pattern, exactly as marching_cubes sets VTK up (spacing 1, iso 0.5,
// 0/1 scalars), so vertices land on edge midpoints. One image and one filter serve all 256
// patterns: a VTK pipeline per pattern cost ~10 ms in all, paid by every `soiq features` call.
CubeCaseTable case_triangles() {
  VtkMessages messages;
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 2);
  image->SetOrigin(0, 0, 0);
  image->SetSpacing(1, 1, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* voxels = static_cast<uint8_t*>(image->GetScalarPointer());
  vtkNew<vtkFlyingEdges3D> surface;
  surface->SetInputData(image);
  surface->SetValue(0, 0.5);
  surface->ComputeNormalsOff();
  surface->ComputeGradientsOff();
  surface->ComputeScalarsOff();
  surface->InterpolateAttributesOff();
  CubeCaseTable table;
  vtkNew<vtkIdList> ids;
  for (int pattern = 0; pattern < 256; ++pattern) {
    for (int bit = 0; bit < 8; ++bit) voxels[bit] = uint8_t((pattern >> bit) & 1);  // VTK id = i + 2j + 4k
    image->Modified();
    surface->Update();
    assert(!messages.has_error() && "VTK marching cubes failed on a single cube");
    vtkPolyData* poly = surface->GetOutput();
    vtkCellArray* polys = poly->GetPolys();
    for (polys->InitTraversal(); polys->GetNextCell(ids);) {
      if (ids->GetNumberOfIds() != 3) continue;
      CubeCaseTriangle t{};
      for (int v = 0; v < 3; ++v) {
        double p[3];
        poly->GetPoint(ids->GetId(v), p);
        for (int a = 0; a < 3; ++a) t[size_t(v)][size_t(a)] = int8_t(std::lround(2 * p[a]));
      }
      table.triangles[size_t(pattern)].push_back(t);
    }
  }
  return table;
}

}  // namespace

const CubeCaseTable& marching_cubes_cases() {
  static const CubeCaseTable table = case_triangles();
  return table;
}

}  // namespace soiq
