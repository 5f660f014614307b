#pragma once
// VTK as the independent oracle for soiq's own mesh parsers: VTK's writers make well-formed files
// in every variant (ASCII, binary, either byte order) and VTK's readers say what those files hold.
// Test-only; the parsers themselves never call VTK.

#include <vtkCellArray.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkOBJReader.h>
#include <vtkPLYReader.h>
#include <vtkPLYWriter.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSTLWriter.h>
#include <vtkSmartPointer.h>

#include <mutex>
#include <string>

#include "core/base/triangle_mesh.h"
#include "core/io/file_extension.h"
#include "core/io/vtk_ply_lock.h"
#include "core/io/vtk_poly_data.h"

namespace soiq::testing_io {

// An ASCII STL written by vtkSTLWriter (write_mesh writes binary only).
inline bool write_ascii_stl_with_vtk(const TriangleMesh& mesh, const std::string& path) {
  vtkNew<vtkSTLWriter> w;
  w->SetFileName(path.c_str());
  w->SetFileTypeToASCII();
  w->SetInputData(to_vtk_poly_data(mesh));
  return w->Write() == 1;
}

// A PLY written by vtkPLYWriter: ASCII, or binary in the given byte order.
inline bool write_ply_with_vtk(const TriangleMesh& mesh, const std::string& path, bool ascii, bool big_endian) {
  std::lock_guard<std::mutex> lock(vtk_ply_mutex());
  vtkNew<vtkPLYWriter> w;
  w->SetFileName(path.c_str());
  if (ascii) {
    w->SetFileTypeToASCII();
  } else {
    w->SetFileTypeToBinary();
    if (big_endian) {
      w->SetDataByteOrderToBigEndian();
    } else {
      w->SetDataByteOrderToLittleEndian();
    }
  }
  w->SetInputData(to_vtk_poly_data(mesh));
  return w->Write() == 1;
}

// What VTK's reader for the file's extension (.stl with merging as soiq used it, .obj, .ply)
// gives: its points (float32 in all three readers, widened) and its triangles.
inline TriangleMesh read_with_vtk(const std::string& path) {
  const std::string ext = file_extension(path);
  vtkSmartPointer<vtkPolyDataAlgorithm> reader;
  std::unique_lock<std::mutex> lock(vtk_ply_mutex(), std::defer_lock);
  if (ext == ".stl") {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->MergingOn();
    r->ScalarTagsOff();
    reader = r;
  } else if (ext == ".obj") {
    reader = vtkSmartPointer<vtkOBJReader>::New();
  } else {
    reader = vtkSmartPointer<vtkPLYReader>::New();
    lock.lock();
  }
  if (auto* stl = vtkSTLReader::SafeDownCast(reader)) stl->SetFileName(path.c_str());
  if (auto* obj = vtkOBJReader::SafeDownCast(reader)) obj->SetFileName(path.c_str());
  if (auto* ply = vtkPLYReader::SafeDownCast(reader)) ply->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* poly = reader->GetOutput();
  TriangleMesh mesh;
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    Vec3 p;
    poly->GetPoint(i, p.data());
    mesh.vertices_mm.push_back(p);
  }
  vtkNew<vtkIdList> ids;
  vtkCellArray* polys = poly->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(ids);) {
    if (ids->GetNumberOfIds() == 3)
      mesh.triangles.push_back({int32_t(ids->GetId(0)), int32_t(ids->GetId(1)), int32_t(ids->GetId(2))});
  }
  return mesh;
}

// `x` rounded to float32. Through a volatile: GCC 12.2 at -O2 (SLP vectorizer) drops the round
// trip on two of three coordinates in `p = {double(float(p[0])), double(float(p[1])), ...}`.
inline double rounded_to_float(double x) {
  volatile float f = float(x);
  return double(f);
}

// `mesh` with every coordinate rounded to float32, as VTK's readers store points.
inline TriangleMesh rounded_to_float(TriangleMesh mesh) {
  for (Vec3& p : mesh.vertices_mm) {
    for (double& c : p) c = rounded_to_float(c);
  }
  return mesh;
}

}  // namespace soiq::testing_io
