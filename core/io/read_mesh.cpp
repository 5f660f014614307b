#include "core/io/read_mesh.h"

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <mutex>

#include "core/io/check_ply_structure.h"
#include "core/io/file_extension.h"
#include "core/io/header_text.h"
#include "core/io/legacy_vtk_geometry.h"
#include "core/io/read_file_bytes.h"
#include "core/io/vtk_messages.h"
#include "core/io/vtk_ply_lock.h"

namespace soiq {
namespace {

// The first `n` bytes of a file (fewer if it is shorter); "" when it cannot be opened.
std::string read_head(const std::string& path, size_t n) {
  std::string head(n, '\0');
  FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return "";
  head.resize(std::fread(head.data(), 1, n, file));
  std::fclose(file);
  return head;
}

// vtkSTLReader decides ASCII vs binary by itself and, on a short binary file, reads what is there
// without complaint. A binary STL is exactly 84 + 50 n bytes, n being the count at byte 80.
Status check_stl_size(const std::string& path, int64_t size) {
  const std::string head = read_head(path, 84);
  uint32_t n = 0;
  if (head.size() == 84) std::memcpy(&n, head.data() + 80, 4);
  const int64_t expected = 84 + 50 * int64_t(n);
  if (head.size() == 84 && expected == size) return ok_status();
  if (trim(head).starts_with("solid")) return ok_status();  // ASCII: VTK checks its syntax
  if (size < 84) {
    return invalid_argument("binary STL '" + path + "' is truncated: " + std::to_string(size) +
                            " bytes, less than the 84-byte header");
  }
  return invalid_argument("binary STL '" + path + "' is truncated or corrupt: its header announces " +
                          std::to_string(n) + " triangles (" + std::to_string(expected) + " bytes) but the file has " +
                          std::to_string(size) + " bytes");
}

// vtkOBJReader trusts face indices; an index outside the vertex list reads out of bounds. Scan
// the `f` and `l` records first and check every vertex, texture and normal index (1-based, or
// negative = relative to the last one defined so far).
Status check_obj_indices(const std::string& path) {
  SOIQ_ASSIGN_OR_RETURN(const std::string text, read_file_bytes(path, "mesh"));
  struct Face {
    int64_t line;
    int64_t index;
    int kind;  // 0 v, 1 vt, 2 vn
  };
  int64_t counts[3] = {0, 0, 0};
  std::vector<Face> positive;  // checked at the end: OBJ allows no forward references, but be lenient
  int64_t line_number = 0;
  size_t start = 0;
  const char* kKindName[3] = {"vertex", "texture coordinate", "normal"};
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string_view line = trim(std::string_view(text).substr(start, end - start));
    start = end + 1;
    ++line_number;
    const auto words = split_words(line);
    if (words.empty()) continue;
    if (words[0] == "v") ++counts[0];
    if (words[0] == "vt") ++counts[1];
    if (words[0] == "vn") ++counts[2];
    if (words[0] != "f" && words[0] != "l") continue;
    for (size_t w = 1; w < words.size(); ++w) {
      std::string_view token = words[w];
      for (int kind = 0; kind < 3 && !token.empty(); ++kind) {
        const size_t slash = token.find('/');
        const std::string_view part = token.substr(0, slash);
        token = slash == std::string_view::npos ? std::string_view() : token.substr(slash + 1);
        if (part.empty() && kind > 0) continue;  // "1//3": no texture index
        const auto index = parse_integer(part);
        if (!index || *index == 0) {
          return invalid_argument("OBJ '" + path + "' line " + std::to_string(line_number) +
                                  ": malformed face index '" + std::string(words[w]) + "'");
        }
        if (*index < 0 && -*index > counts[kind]) {
          return invalid_argument("OBJ '" + path + "' line " + std::to_string(line_number) + ": face index " +
                                  std::to_string(*index) + " is out of range (" + std::to_string(counts[kind]) + " " +
                                  kKindName[kind] + "s defined so far)");
        }
        if (*index < 0) {
          // vtkOBJReader does not resolve relative indices; refuse rather than misread.
          return invalid_argument("OBJ '" + path + "' line " + std::to_string(line_number) +
                                  ": relative (negative) face indices are not supported");
        }
        positive.push_back({line_number, *index, kind});
      }
    }
  }
  for (const Face& f : positive) {
    if (f.index > counts[f.kind]) {
      return invalid_argument("OBJ '" + path + "' line " + std::to_string(f.line) + ": face index " +
                              std::to_string(f.index) + " is out of range (the file has " +
                              std::to_string(counts[f.kind]) + " " + kKindName[f.kind] + "s)");
    }
  }
  return ok_status();
}

vtkSmartPointer<vtkAlgorithm> make_reader(const std::string& ext, const std::string& path) {
  if (ext == ".stl") {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(path.c_str());
    r->MergingOn();  // share coincident vertices (exact equality) so closed surfaces are watertight
    r->ScalarTagsOff();
    return r;
  }
  if (ext == ".obj") {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (ext == ".ply") {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  if (ext == ".vtk") {
    auto r = vtkSmartPointer<vtkPolyDataReader>::New();
    r->SetFileName(path.c_str());
    return r;
  }
  auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
  r->SetFileName(path.c_str());
  return r;
}

// Every point id of every polygon and strip must name a point; readers do not all check.
Status check_cell_ids(vtkPolyData* poly, const std::string& path) {
  const vtkIdType points = poly->GetNumberOfPoints();
  for (vtkCellArray* cells : {poly->GetPolys(), poly->GetStrips()}) {
    if (cells == nullptr) continue;
    const vtkIdType n = cells->GetNumberOfConnectivityIds();
    for (vtkIdType k = 0; k < n; ++k) {
      const vtkIdType id = cells->GetConnectivityArray()->GetComponent(k, 0);
      if (id < 0 || id >= points) {
        return invalid_argument("mesh '" + path + "' has a face index " + std::to_string(id) +
                                " out of range (it has " + std::to_string(points) + " vertices)");
      }
    }
  }
  return ok_status();
}

}  // namespace

Result<TriangleMesh> read_mesh(const std::string& path, bool ras) {
  const std::string ext = file_extension(path);
  if (ext != ".stl" && ext != ".obj" && ext != ".ply" && ext != ".vtk" && ext != ".vtp") {
    return invalid_argument("unknown mesh extension '" + ext + "' of '" + path +
                            "'; soiq reads .stl, .obj, .ply, .vtk and .vtp");
  }
  SOIQ_ASSIGN_OR_RETURN(const int64_t size, input_file_size(path, "mesh"));
  if (size == 0) return invalid_argument("mesh file '" + path + "' is empty");
  if (ext == ".stl") SOIQ_RETURN_IF_ERROR(check_stl_size(path, size));
  if (ext == ".obj") SOIQ_RETURN_IF_ERROR(check_obj_indices(path));
  if (ext == ".ply") {
    SOIQ_ASSIGN_OR_RETURN(const std::string bytes, read_file_bytes(path, "mesh"));
    SOIQ_RETURN_IF_ERROR(check_ply_structure(bytes, path));
  }

  std::string vtk_geometry;
  if (ext == ".vtk") {
    SOIQ_ASSIGN_OR_RETURN(const std::string bytes, read_file_bytes(path, "mesh"));
    SOIQ_ASSIGN_OR_RETURN(vtk_geometry, legacy_vtk_geometry(bytes, path));
  }

  VtkMessages messages;
  vtkSmartPointer<vtkAlgorithm> reader = make_reader(ext, path);
  if (ext == ".vtk") {
    // Parse only the checked geometry, from memory (see legacy_vtk_geometry.h).
    auto* legacy = static_cast<vtkPolyDataReader*>(reader.Get());
    legacy->ReadFromInputStringOn();
    legacy->SetInputString(vtk_geometry.data(), int(vtk_geometry.size()));
  }
  {
    std::unique_lock<std::mutex> ply_lock(vtk_ply_mutex(), std::defer_lock);
    if (ext == ".ply") ply_lock.lock();
    reader->Update();
  }
  vtkPolyData* poly = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (messages.has_error() || poly == nullptr) {
    const std::string why = messages.last_error();
    return invalid_argument("cannot read mesh '" + path + "': " + (why.empty() ? "malformed file" : why));
  }
  SOIQ_RETURN_IF_ERROR(check_cell_ids(poly, path));
  if (poly->GetNumberOfPoints() > std::numeric_limits<int32_t>::max()) {
    return resource_exhausted("mesh '" + path + "' has more than 2^31 vertices");
  }

  // Triangulate polygons and strips (ear cutting for non-convex polygons); drop lines and points.
  vtkNew<vtkTriangleFilter> triangulate;
  triangulate->SetInputData(poly);
  triangulate->PassVertsOff();
  triangulate->PassLinesOff();
  triangulate->Update();
  vtkPolyData* triangles = triangulate->GetOutput();

  TriangleMesh mesh;
  const vtkIdType points = triangles->GetNumberOfPoints();
  mesh.vertices_mm.resize(size_t(points));
  const double sign = ras ? -1.0 : 1.0;
  for (vtkIdType i = 0; i < points; ++i) {
    double p[3];
    triangles->GetPoint(i, p);
    mesh.vertices_mm[size_t(i)] = {sign * p[0], sign * p[1], p[2]};
  }
  vtkCellArray* polys = triangles->GetPolys();
  vtkNew<vtkIdList> ids;
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() != 3) continue;
    mesh.triangles.push_back({int32_t(ids->GetId(0)), int32_t(ids->GetId(1)), int32_t(ids->GetId(2))});
  }
  if (mesh.triangles.empty()) return invalid_argument("mesh '" + path + "' contains no triangles");
  return mesh;
}

}  // namespace soiq
