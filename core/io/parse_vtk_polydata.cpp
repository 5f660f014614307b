#include "core/io/parse_vtk_polydata.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataReader.h>

#include <cstdint>
#include <limits>

#include "core/io/legacy_vtk_geometry.h"
#include "core/io/vtk_messages.h"

namespace soiq {
namespace {

// Every point id of every polygon and strip must name a point; the XML reader does not check.
Status check_cell_ids(vtkPolyData* poly, const std::string& name) {
  const vtkIdType points = poly->GetNumberOfPoints();
  for (vtkCellArray* cells : {poly->GetPolys(), poly->GetStrips()}) {
    if (cells == nullptr) continue;
    const vtkIdType n = cells->GetNumberOfConnectivityIds();
    for (vtkIdType k = 0; k < n; ++k) {
      const vtkIdType id = cells->GetConnectivityArray()->GetComponent(k, 0);
      if (id < 0 || id >= points) {
        return invalid_argument("mesh '" + name + "' has a face index " + std::to_string(id) +
                                " out of range (it has " + std::to_string(points) + " vertices)");
      }
    }
  }
  return ok_status();
}

}  // namespace

Result<TriangleMesh> parse_vtk_polydata(std::string_view bytes, bool xml, const std::string& name) {
  VtkMessages messages;
  vtkSmartPointer<vtkAlgorithm> reader;
  std::string geometry;  // the legacy reader keeps a pointer to it until Update() returns
  if (xml) {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->ReadFromInputStringOn();
    r->SetInputString(std::string(bytes));
    reader = r;
  } else {
    // VTK 9.1's legacy reader trusts every count: it only sees the checked geometry.
    SOIQ_ASSIGN_OR_RETURN(geometry, legacy_vtk_geometry(std::string(bytes), name));
    auto r = vtkSmartPointer<vtkPolyDataReader>::New();
    r->ReadFromInputStringOn();
    r->SetInputString(geometry.data(), int(geometry.size()));
    reader = r;
  }
  reader->Update();
  vtkPolyData* poly = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (messages.has_error() || poly == nullptr) {
    const std::string why = messages.last_error();
    return invalid_argument("cannot read mesh '" + name + "': " + (why.empty() ? "malformed file" : why));
  }
  SOIQ_RETURN_IF_ERROR(check_cell_ids(poly, name));
  if (poly->GetNumberOfPoints() > std::numeric_limits<int32_t>::max()) {
    return resource_exhausted("mesh '" + name + "' has more than 2^31 vertices");
  }

  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(poly);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  vtkPolyData* triangles = triangulate->GetOutput();

  TriangleMesh mesh;
  const vtkIdType points = triangles->GetNumberOfPoints();
  mesh.vertices_mm.resize(size_t(points));
  for (vtkIdType i = 0; i < points; ++i) triangles->GetPoint(i, mesh.vertices_mm[size_t(i)].data());
  vtkCellArray* polys = triangles->GetPolys();
  vtkNew<vtkIdList> ids;
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() != 3) continue;
    mesh.triangles.push_back({int32_t(ids->GetId(0)), int32_t(ids->GetId(1)), int32_t(ids->GetId(2))});
  }
  return mesh;
}

}  // namespace soiq
