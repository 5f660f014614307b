#include "core/io/parse_vtk_polydata.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkTypeInt64Array.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "core/io/legacy_vtk_geometry.h"
#include "core/io/vtk_messages.h"
#include "core/io/vtk_xml_polydata.h"

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

vtkSmartPointer<vtkCellArray> cell_array(const VtkXmlCells& cells) {
  vtkNew<vtkTypeInt64Array> offsets, connectivity;
  offsets->SetNumberOfValues(vtkIdType(cells.offsets.size()));
  for (size_t i = 0; i < cells.offsets.size(); ++i) offsets->SetValue(vtkIdType(i), cells.offsets[i]);
  connectivity->SetNumberOfValues(vtkIdType(cells.connectivity.size()));
  for (size_t i = 0; i < cells.connectivity.size(); ++i) connectivity->SetValue(vtkIdType(i), cells.connectivity[i]);
  auto array = vtkSmartPointer<vtkCellArray>::New();
  array->SetData(offsets, connectivity);
  return array;
}

// The arrays soiq decoded itself (vtk_xml_polydata.h) as the polydata VTK's reader would give.
vtkSmartPointer<vtkPolyData> polydata_of(const VtkXmlPolyData& xml) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(vtkIdType(xml.points.size() / 3));
  for (size_t i = 0; i < xml.points.size() / 3; ++i) points->SetPoint(vtkIdType(i), &xml.points[3 * i]);
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cell_array(xml.polys));
  poly->SetStrips(cell_array(xml.strips));
  return poly;
}

}  // namespace

Result<TriangleMesh> parse_vtk_polydata(std::string_view bytes, bool xml, const std::string& name) {
  VtkMessages messages;
  vtkSmartPointer<vtkPolyData> poly;
  if (xml) {
    // VTK 9.1's XML reader allocates what the arrays' headers claim: soiq decodes them itself.
    SOIQ_ASSIGN_OR_RETURN(const VtkXmlPolyData arrays, read_vtk_xml_polydata(bytes, name));
    poly = polydata_of(arrays);
  } else {
    // VTK 9.1's legacy reader trusts every count: it only sees the checked geometry.
    SOIQ_ASSIGN_OR_RETURN(const std::string geometry, legacy_vtk_geometry(std::string(bytes), name));
    vtkNew<vtkPolyDataReader> reader;
    reader->ReadFromInputStringOn();
    reader->SetInputString(geometry.data(), int(geometry.size()));
    reader->Update();
    poly = reader->GetOutput();
    if (messages.has_error() || poly == nullptr) {
      const std::string why = messages.last_error();
      return invalid_argument("cannot read mesh '" + name + "': " + (why.empty() ? "malformed file" : why));
    }
  }
  SOIQ_RETURN_IF_ERROR(check_cell_ids(poly, name));
  // The legacy reader takes binary NaN and infinities as they are; no surface has them.
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    double p[3];
    poly->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      return invalid_argument("mesh '" + name + "' has vertex " + std::to_string(i) + " that is not a finite number");
  }
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
