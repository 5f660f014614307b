#include "bench/peers_vtk.h"

#include <vtkCellArray.h>
#include <vtkDataArray.h>
#include <vtkImageStencilData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataToImageStencil.h>
#include <vtkSelectEnclosedPoints.h>
#include <vtkSmartPointer.h>

#include <cstring>

namespace soiq::bench {

namespace {

// Where VTK sees the grid: origin and spacing of an axis-aligned image, and the map of our LPS
// points into that frame.
struct VtkFrame {
  Vec3 origin_mm{0, 0, 0};
  Vec3 spacing_mm{1, 1, 1};
  bool identity = true;
};

VtkFrame frame_of(const ImageGeometry& g) {
  VtkFrame f;
  f.identity = g.direction == identity3();
  f.spacing_mm = g.spacing_mm;
  if (f.identity) f.origin_mm = g.origin_mm;
  return f;
}

Vec3 to_frame(const ImageGeometry& g, const VtkFrame& f, const Vec3& p) {
  if (f.identity) return p;
  const Vec3 u = g.physical_to_index(p);
  return {u[0] * g.spacing_mm[0], u[1] * g.spacing_mm[1], u[2] * g.spacing_mm[2]};
}

vtkSmartPointer<vtkPolyData> to_polydata(const TriangleMesh& mesh, const ImageGeometry& g, const VtkFrame& f) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(vtkIdType(mesh.vertices_mm.size()));
  for (size_t v = 0; v < mesh.vertices_mm.size(); ++v) {
    const Vec3 q = to_frame(g, f, mesh.vertices_mm[v]);
    points->SetPoint(vtkIdType(v), q.data());
  }
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateExact(vtkIdType(mesh.triangles.size()), vtkIdType(3 * mesh.triangles.size()));
  for (const auto& t : mesh.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    cells->InsertNextCell(3, ids);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  return poly;
}

}  // namespace

Result<Conversion> prepare_vtk_stencil(const TriangleMesh& mesh, const ImageGeometry& geometry) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  const VtkFrame f = frame_of(geometry);
  vtkSmartPointer<vtkPolyData> poly = to_polydata(mesh, geometry, f);
  return Conversion([poly, f, geometry]() -> Result<Mask> {
    const int nx = int(geometry.dims[0]), ny = int(geometry.dims[1]), nz = int(geometry.dims[2]);
    auto stencil = vtkSmartPointer<vtkPolyDataToImageStencil>::New();
    stencil->SetInputData(poly);
    stencil->SetOutputOrigin(f.origin_mm[0], f.origin_mm[1], f.origin_mm[2]);
    stencil->SetOutputSpacing(f.spacing_mm[0], f.spacing_mm[1], f.spacing_mm[2]);
    stencil->SetOutputWholeExtent(0, nx - 1, 0, ny - 1, 0, nz - 1);
    stencil->SetTolerance(0);
    stencil->Update();
    vtkImageStencilData* data = stencil->GetOutput();
    Mask m;
    m.geometry = geometry;
    m.voxels.assign(size_t(geometry.voxel_count()), 0);
    for (int z = 0; z < nz; ++z) {
      for (int y = 0; y < ny; ++y) {
        uint8_t* row = m.voxels.data() + size_t(nx) * (size_t(y) + size_t(ny) * size_t(z));
        int iter = 0, r1 = 0, r2 = 0;
        while (data->GetNextExtent(r1, r2, 0, nx - 1, y, z, iter)) {
          if (r2 >= r1) std::memset(row + r1, 1, size_t(r2 - r1 + 1));
        }
      }
    }
    return m;
  });
}

Result<Conversion> prepare_vtk_enclosed(const TriangleMesh& mesh, const ImageGeometry& geometry, int threads) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  SOIQ_RETURN_IF_ERROR(check_grid_size(geometry, 200'000'000));
  // vtkSMPTools.h does not compile as C++20 in VTK 9.1 (a template-id constructor), so VTK's SMP
  // back-end keeps its default thread count; `threads` is recorded by the caller only.
  static_cast<void>(threads);
  const VtkFrame f = frame_of(geometry);
  vtkSmartPointer<vtkPolyData> surface = to_polydata(mesh, geometry, f);
  auto centres = vtkSmartPointer<vtkPoints>::New();
  centres->SetDataTypeToDouble();
  centres->SetNumberOfPoints(vtkIdType(geometry.voxel_count()));
  vtkIdType n = 0;
  for (int64_t k = 0; k < geometry.dims[2]; ++k) {
    for (int64_t j = 0; j < geometry.dims[1]; ++j) {
      for (int64_t i = 0; i < geometry.dims[0]; ++i) {
        const double p[3] = {f.origin_mm[0] + double(i) * f.spacing_mm[0], f.origin_mm[1] + double(j) * f.spacing_mm[1],
                             f.origin_mm[2] + double(k) * f.spacing_mm[2]};
        centres->SetPoint(n++, p);
      }
    }
  }
  auto points = vtkSmartPointer<vtkPolyData>::New();
  points->SetPoints(centres);
  return Conversion([surface, points, geometry]() -> Result<Mask> {
    auto select = vtkSmartPointer<vtkSelectEnclosedPoints>::New();
    select->SetInputData(points);
    select->SetSurfaceData(surface);
    select->Update();
    Mask m;
    m.geometry = geometry;
    m.voxels.assign(size_t(geometry.voxel_count()), 0);
    vtkDataArray* selected = select->GetOutput()->GetPointData()->GetArray("SelectedPoints");
    if (selected == nullptr) return internal_error("vtkSelectEnclosedPoints gave no SelectedPoints array");
    for (vtkIdType v = 0; v < vtkIdType(m.voxels.size()); ++v) m.voxels[size_t(v)] = selected->GetTuple1(v) != 0;
    return m;
  });
}

}  // namespace soiq::bench
