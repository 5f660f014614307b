#include "core/io/marching_cubes.h"

#include <vtkCellArray.h>
#include <vtkFlyingEdges3D.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include "core/geometry/mesh_defects.h"
#include "core/io/vtk_messages.h"

namespace soiq {
namespace {

// Index bounds [lo, hi] of the nonzero voxels; hi[0] < 0 when there is none.
struct VoxelBox {
  int64_t lo[3], hi[3];
};

VoxelBox nonzero_box(const Mask& mask) {
  const int64_t nx = mask.geometry.dims[0], ny = mask.geometry.dims[1], nz = mask.geometry.dims[2];
  VoxelBox box{{nx, ny, nz}, {-1, -1, -1}};
  for (int64_t k = 0; k < nz; ++k) {
    for (int64_t j = 0; j < ny; ++j) {
      const uint8_t* row = mask.voxels.data() + nx * (j + ny * k);
      for (int64_t i = 0; i < nx; ++i) {
        if (row[i] == 0) continue;
        box.lo[0] = std::min(box.lo[0], i), box.hi[0] = std::max(box.hi[0], i);
        box.lo[1] = std::min(box.lo[1], j), box.hi[1] = std::max(box.hi[1], j);
        box.lo[2] = std::min(box.lo[2], k), box.hi[2] = std::max(box.hi[2], k);
      }
    }
  }
  return box;
}

}  // namespace

Result<TriangleMesh> marching_cubes(const Mask& mask) {
  const ImageGeometry& g = mask.geometry;
  SOIQ_RETURN_IF_ERROR(validate_geometry(g));
  if (mask.voxels.size() != size_t(g.voxel_count())) {
    return invalid_argument("mask has " + std::to_string(mask.voxels.size()) + " voxels but its grid is " +
                            describe(g));
  }
  // Bounding box of the inside voxels: marching cubes only needs that part of the grid.
  const int64_t nx = g.dims[0], ny = g.dims[1];
  const VoxelBox box = nonzero_box(mask);
  const int64_t* lo = box.lo;
  const int64_t* hi = box.hi;
  TriangleMesh mesh;
  if (hi[0] < 0) return mesh;  // empty mask: empty surface

  // The box plus one voxel of zeros on every side, so the surface closes at the grid border.
  // Crop voxel (a,b,c) is mask voxel (a,b,c) + lo - 1.
  const int64_t cx = hi[0] - lo[0] + 3, cy = hi[1] - lo[1] + 3, cz = hi[2] - lo[2] + 3;
  if (cx > std::numeric_limits<int>::max() || cy > std::numeric_limits<int>::max() ||
      cz > std::numeric_limits<int>::max()) {
    return resource_exhausted("mask of " + describe(g) + " is too large for VTK's marching cubes");
  }
  VtkMessages messages;
  vtkNew<vtkImageData> image;
  image->SetDimensions(int(cx), int(cy), int(cz));
  image->SetOrigin(0, 0, 0);
  image->SetSpacing(1, 1, 1);  // index space: vertices land exactly on x.5 edge midpoints
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* crop = static_cast<uint8_t*>(image->GetScalarPointer());
  std::memset(crop, 0, size_t(cx * cy * cz));
  for (int64_t k = lo[2]; k <= hi[2]; ++k) {
    for (int64_t j = lo[1]; j <= hi[1]; ++j) {
      const uint8_t* src = mask.voxels.data() + lo[0] + nx * (j + ny * k);
      uint8_t* dst = crop + 1 + cx * ((j - lo[1] + 1) + cy * (k - lo[2] + 1));
      // Any nonzero value is inside: normalise to 0/1 so the 0.5 crossing is an exact midpoint.
      for (int64_t i = 0; i <= hi[0] - lo[0]; ++i) dst[i] = src[i] != 0 ? 1 : 0;
    }
  }

  // Flying edges uses VTK's marching-cubes case table (so the same triangles as vtkMarchingCubes)
  // and shares every edge vertex between the cubes around it by construction: no point merging
  // needed, and the surface of a 0/1 volume is closed. Interpolation at iso 0.5 between 0 and 1
  // gives t = 0.5 exactly.
  vtkNew<vtkFlyingEdges3D> surface;
  surface->SetInputData(image);
  surface->SetValue(0, 0.5);
  surface->ComputeNormalsOff();
  surface->ComputeGradientsOff();
  surface->ComputeScalarsOff();
  surface->InterpolateAttributesOff();
  surface->Update();
  if (messages.has_error()) return internal_error("VTK marching cubes failed: " + messages.last_error());
  vtkPolyData* poly = surface->GetOutput();

  const Vec3 offset{double(lo[0] - 1), double(lo[1] - 1), double(lo[2] - 1)};
  const vtkIdType points = poly->GetNumberOfPoints();
  mesh.vertices_mm.resize(size_t(points));
  for (vtkIdType n = 0; n < points; ++n) {
    double p[3];
    poly->GetPoint(n, p);
    mesh.vertices_mm[size_t(n)] = g.index_to_physical({p[0] + offset[0], p[1] + offset[1], p[2] + offset[2]});
  }
  vtkCellArray* polys = poly->GetPolys();
  mesh.triangles.reserve(size_t(polys->GetNumberOfCells()));
  vtkNew<vtkIdList> ids;
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() != 3) continue;
    mesh.triangles.push_back({int32_t(ids->GetId(0)), int32_t(ids->GetId(1)), int32_t(ids->GetId(2))});
  }
  // VTK orients triangles by the scalar gradient, consistently over the whole surface, so one
  // global flip suffices. Measuring the signed volume after the mapping to LPS also accounts for
  // a direction matrix with negative determinant, which mirrors the surface.
  orient_outward(mesh);
  return mesh;
}

}  // namespace soiq
