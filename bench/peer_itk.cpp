#include "bench/peer_itk.h"

#ifdef SOIQ_HAVE_ITK
#include <itkImage.h>
#include <itkMesh.h>
#include <itkTriangleCell.h>
#include <itkTriangleMeshToBinaryImageFilter.h>

#include <cstring>
#endif

namespace soiq::bench {

#ifdef SOIQ_HAVE_ITK

bool itk_available() { return true; }

Result<Conversion> prepare_itk(const TriangleMesh& mesh, const ImageGeometry& geometry) {
  SOIQ_RETURN_IF_ERROR(validate_geometry(geometry));
  using MeshType = itk::Mesh<double, 3>;
  using ImageType = itk::Image<unsigned char, 3>;
  using CellType = MeshType::CellType;
  using TriangleType = itk::TriangleCell<CellType>;
  using FilterType = itk::TriangleMeshToBinaryImageFilter<MeshType, ImageType>;

  MeshType::Pointer itk_mesh = MeshType::New();
  for (size_t v = 0; v < mesh.vertices_mm.size(); ++v) {
    MeshType::PointType p;
    for (int c = 0; c < 3; ++c) p[c] = mesh.vertices_mm[v][c];
    itk_mesh->SetPoint(MeshType::PointIdentifier(v), p);
  }
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    CellType::CellAutoPointer cell;
    cell.TakeOwnership(new TriangleType);
    for (int c = 0; c < 3; ++c) cell->SetPointId(c, MeshType::PointIdentifier(mesh.triangles[t][c]));
    itk_mesh->SetCell(MeshType::CellIdentifier(t), cell);
  }

  return Conversion([itk_mesh, geometry]() -> Result<Mask> {
    FilterType::Pointer filter = FilterType::New();
    filter->SetInput(itk_mesh);
    FilterType::PointType origin;
    FilterType::SpacingType spacing;
    FilterType::DirectionType direction;
    FilterType::SizeType size;
    FilterType::IndexType index;
    for (int r = 0; r < 3; ++r) {
      origin[r] = geometry.origin_mm[r];
      spacing[r] = geometry.spacing_mm[r];
      size[r] = itk::SizeValueType(geometry.dims[r]);
      index[r] = 0;
      for (int c = 0; c < 3; ++c) direction(r, c) = geometry.direction[r][c];
    }
    filter->SetOrigin(origin);
    filter->SetSpacing(spacing);
    filter->SetDirection(direction);
    filter->SetSize(size);
    filter->SetIndex(index);
    filter->SetInsideValue(1);
    filter->SetOutsideValue(0);
    try {
      filter->Update();
    } catch (const itk::ExceptionObject& e) {
      return internal_error(std::string("itk::TriangleMeshToBinaryImageFilter failed: ") + e.GetDescription());
    }
    Mask m;
    m.geometry = geometry;
    m.voxels.resize(size_t(geometry.voxel_count()));
    std::memcpy(m.voxels.data(), filter->GetOutput()->GetBufferPointer(), m.voxels.size());
    return m;
  });
}

#else

bool itk_available() { return false; }

Result<Conversion> prepare_itk(const TriangleMesh&, const ImageGeometry&) {
  return unimplemented("this soiq-bench was built without ITK; install libinsighttoolkit5-dev and rebuild");
}

#endif

}  // namespace soiq::bench
