#include "core/io/marching_cubes_cases.h"

#include <vtkCellArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

#include "core/io/vtk_messages.h"

namespace soiq {
namespace {

// A filter set up exactly as marching_cubes sets VTK up (spacing 1, iso 0.5, 0/1 scalars), so
// vertices land on edge midpoints.
void configure(vtkFlyingEdges3D& surface) {
  surface.SetValue(0, 0.5);
  surface.ComputeNormalsOff();
  surface.ComputeGradientsOff();
  surface.ComputeScalarsOff();
  surface.InterpolateAttributesOff();
}

vtkNew<vtkImageData> unit_image(int nx, int ny, int nz) {
  vtkNew<vtkImageData> image;
  image->SetDimensions(nx, ny, nz);
  image->SetOrigin(0, 0, 0);
  image->SetSpacing(1, 1, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  std::fill_n(static_cast<uint8_t*>(image->GetScalarPointer()), size_t(nx) * size_t(ny) * size_t(nz), uint8_t(0));
  return image;
}

// Calls f(triangle) for each triangle of the filter's output, in doubled coordinates.
template <typename F>
void for_each_triangle(vtkPolyData* poly, F&& f) {
  vtkNew<vtkIdList> ids;
  vtkCellArray* polys = poly->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() != 3) continue;
    std::array<std::array<int64_t, 3>, 3> t{};
    for (int v = 0; v < 3; ++v) {
      double p[3];
      poly->GetPoint(ids->GetId(v), p);
      for (int a = 0; a < 3; ++a) t[size_t(v)][size_t(a)] = std::llround(2 * p[a]);
    }
    f(t);
  }
}

}  // namespace

// All 256 patterns in one image and one run: pattern p's cube at x = 4p, 4p + 1, then two layers
// of zeros. A triangle of that cube has every doubled x in [8p, 8p + 2] and, marching cubes being
// a manifold surface, never all of them on one face of the cube (x = 8p or 8p + 2); each triangle of the cubes
// between patterns has some x outside that range or all of them on a face plane. So the cube of
// every triangle is known, and the table is VTK's exactly (marching_cubes_cases_one_by_one, the
// tests' oracle, runs each pattern alone).
CubeCaseTable read_marching_cubes_cases() {
  VtkMessages messages;
  vtkNew<vtkImageData> image = unit_image(4 * 256, 2, 2);
  auto* voxels = static_cast<uint8_t*>(image->GetScalarPointer());
  for (int p = 0; p < 256; ++p) {
    for (int bit = 0; bit < 8; ++bit) {
      const int di = bit & 1, dj = (bit >> 1) & 1, dk = (bit >> 2) & 1;
      voxels[size_t(4 * p + di + 4 * 256 * (dj + 2 * dk))] = uint8_t((p >> bit) & 1);
    }
  }
  vtkNew<vtkFlyingEdges3D> surface;
  configure(*surface);
  surface->SetInputData(image);
  surface->Update();
  assert(!messages.has_error() && "VTK marching cubes failed on the pattern image");
  CubeCaseTable table;
  for_each_triangle(surface->GetOutput(), [&](const std::array<std::array<int64_t, 3>, 3>& t) {
    const int64_t lo = std::min({t[0][0], t[1][0], t[2][0]}), hi = std::max({t[0][0], t[1][0], t[2][0]});
    const int64_t p = lo / 8;
    const bool on_a_face = lo == hi && lo != 8 * p + 1;   // all at x = 8p or all at 8p + 2
    if (p >= 256 || hi > 8 * p + 2 || on_a_face) return;  // another cube's
    CubeCaseTriangle local{};
    for (size_t v = 0; v < 3; ++v) {
      local[v] = {int8_t(t[v][0] - 8 * p), int8_t(t[v][1]), int8_t(t[v][2])};
    }
    table.triangles[size_t(p)].push_back(local);
  });
  return table;
}

CubeCaseTable marching_cubes_cases_one_by_one() {
  VtkMessages messages;
  vtkNew<vtkImageData> image = unit_image(2, 2, 2);
  auto* voxels = static_cast<uint8_t*>(image->GetScalarPointer());
  vtkNew<vtkFlyingEdges3D> surface;
  configure(*surface);
  surface->SetInputData(image);
  CubeCaseTable table;
  for (int pattern = 0; pattern < 256; ++pattern) {
    for (int bit = 0; bit < 8; ++bit) voxels[bit] = uint8_t((pattern >> bit) & 1);  // VTK id = i + 2j + 4k
    image->Modified();
    surface->Update();
    assert(!messages.has_error() && "VTK marching cubes failed on a single cube");
    for_each_triangle(surface->GetOutput(), [&](const std::array<std::array<int64_t, 3>, 3>& t) {
      CubeCaseTriangle local{};
      for (size_t v = 0; v < 3; ++v) local[v] = {int8_t(t[v][0]), int8_t(t[v][1]), int8_t(t[v][2])};
      table.triangles[size_t(pattern)].push_back(local);
    });
  }
  return table;
}

const CubeCaseTable& marching_cubes_cases() {
  static const CubeCaseTable table = read_marching_cubes_cases();
  return table;
}

}  // namespace soiq
