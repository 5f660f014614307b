#pragma once
// A TriangleMesh as VTK's vtkPolyData, for VTK's writers and filters: double coordinates (LPS mm,
// unchanged) and one triangle cell per triangle, in order. O(vertices + triangles).

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "core/base/triangle_mesh.h"

namespace soiq {

vtkSmartPointer<vtkPolyData> to_vtk_poly_data(const TriangleMesh& mesh);

}  // namespace soiq
