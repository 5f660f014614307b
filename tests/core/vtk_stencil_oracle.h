#pragma once
// Test support: VTK's vtkPolyDataToImageStencil as an independent oracle of the 1D method on grids
// the test maps itself (sheared, unevenly spaced): the mesh's vertices are mapped into an index
// space by the test's own function, and VTK cuts and fills it on the unit lattice 0..dims-1.
// Header-only (tests/core lists its sources).

#include <vtkCellArray.h>
#include <vtkImageStencilData.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataToImageStencil.h>

#include <array>
#include <cstdint>
#include <vector>

#include "core/base/triangle_mesh.h"
#include "core/base/vec3.h"

namespace soiq::testing {

inline double det3(const Mat3& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

// x with a x = d, by Cramer's rule: an inverse that shares nothing with ImageGeometry's.
inline Vec3 cramer_solve(const Mat3& a, const Vec3& d) {
  const double whole = det3(a);
  Vec3 out{};
  for (size_t c = 0; c < 3; ++c) {
    Mat3 m = a;
    for (size_t r = 0; r < 3; ++r) m[r][c] = d[r];
    out[c] = det3(m) / whole;
  }
  return out;
}

// The voxels (i fastest over dims) whose centres VTK puts inside the mesh mapped by `to_index`.
template <typename ToIndex>
std::vector<uint8_t> vtk_stencil(const TriangleMesh& mesh, ToIndex&& to_index, const std::array<int64_t, 3>& dims) {
  vtkNew<vtkPoints> points;
  for (const Vec3& v : mesh.vertices_mm) {
    const Vec3 u = to_index(v);
    points->InsertNextPoint(u[0], u[1], u[2]);
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& t : mesh.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    polys->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetPolys(polys);
  vtkNew<vtkPolyDataToImageStencil> stencil;
  stencil->SetInputData(poly);
  stencil->SetOutputOrigin(0, 0, 0);
  stencil->SetOutputSpacing(1, 1, 1);
  stencil->SetOutputWholeExtent(0, int(dims[0] - 1), 0, int(dims[1] - 1), 0, int(dims[2] - 1));
  stencil->SetTolerance(0);
  stencil->Update();
  vtkImageStencilData* data = stencil->GetOutput();
  std::vector<uint8_t> mask(size_t(dims[0] * dims[1] * dims[2]), 0);
  for (int k = 0; k < int(dims[2]); ++k) {
    for (int j = 0; j < int(dims[1]); ++j) {
      int iter = 0, r1 = 0, r2 = 0;
      while (data->GetNextExtent(r1, r2, 0, int(dims[0] - 1), j, k, iter))
        for (int i = r1; i <= r2; ++i) mask[size_t(i + dims[0] * (j + dims[1] * k))] = 1;
    }
  }
  return mask;
}

}  // namespace soiq::testing
