#include "core/io/write_mesh.h"

#include <unistd.h>
#include <vtkDataWriter.h>
#include <vtkErrorCode.h>
#include <vtkNew.h>
#include <vtkOBJWriter.h>
#include <vtkPLYWriter.h>
#include <vtkPolyData.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLWriter.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataWriter.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <system_error>

#include "core/io/file_extension.h"
#include "core/io/header_text.h"
#include "core/io/vtk_messages.h"
#include "core/io/vtk_ply_lock.h"
#include "core/io/vtk_poly_data.h"
#include "core/io/write_file_bytes.h"

namespace soiq {
namespace {

vtkSmartPointer<vtkWriter> make_writer(const std::string& ext, const std::string& file) {
  if (ext == ".stl") {
    auto w = vtkSmartPointer<vtkSTLWriter>::New();
    w->SetFileName(file.c_str());
    w->SetFileTypeToBinary();  // STL stores float32 whatever the file type
    return w;
  }
  if (ext == ".obj") {
    auto w = vtkSmartPointer<vtkOBJWriter>::New();
    w->SetFileName(file.c_str());
    return w;
  }
  if (ext == ".ply") {
    auto w = vtkSmartPointer<vtkPLYWriter>::New();
    w->SetFileName(file.c_str());
    w->SetFileTypeToBinary();
    return w;
  }
  if (ext == ".vtk") {
    auto w = vtkSmartPointer<vtkPolyDataWriter>::New();
    w->SetFileName(file.c_str());
    w->SetFileTypeToBinary();  // binary doubles round-trip exactly; ASCII would round them
    // Legacy format 4.2, which VTK < 9 and ITK's mesh readers also read.
    w->SetFileVersion(vtkDataWriter::VTK_LEGACY_READER_VERSION_4_2);
    return w;
  }
  return nullptr;  // .vtp: vtkXMLPolyDataWriter is not a vtkWriter, see write_with
}

// Runs the format's writer; returns vtkErrorCode (NoError on success).
unsigned long write_with(const std::string& ext, const std::string& file, vtkPolyData* poly) {
  if (ext == ".vtp") {
    vtkNew<vtkXMLPolyDataWriter> w;  // appended, zlib-compressed, points kept as double
    w->SetFileName(file.c_str());
    w->SetInputData(poly);
    const int ok = w->Write();
    return ok == 1 ? w->GetErrorCode() : std::max<unsigned long>(w->GetErrorCode(), vtkErrorCode::UnknownError);
  }
  vtkSmartPointer<vtkWriter> w = make_writer(ext, file);
  w->SetInputData(poly);
  std::unique_lock<std::mutex> ply_lock(vtk_ply_mutex(), std::defer_lock);
  if (ext == ".ply") ply_lock.lock();
  const int ok = w->Write();
  return ok == 1 ? w->GetErrorCode() : std::max<unsigned long>(w->GetErrorCode(), vtkErrorCode::UnknownError);
}

}  // namespace

Status write_mesh(const TriangleMesh& mesh, const std::string& path) {
  const std::string ext = file_extension(path);
  if (ext != ".stl" && ext != ".obj" && ext != ".ply" && ext != ".vtk" && ext != ".vtp") {
    return invalid_argument("unknown mesh extension '" + ext + "' of '" + path +
                            "'; soiq writes .stl, .obj, .ply, .vtk and .vtp");
  }
  const int64_t vertices = int64_t(mesh.vertices_mm.size());
  for (const auto& t : mesh.triangles) {
    for (const int32_t v : t) {
      if (v < 0 || v >= vertices) {
        return invalid_argument("cannot write mesh '" + path + "': triangle vertex index " + std::to_string(v) +
                                " is out of range (" + std::to_string(vertices) + " vertices)");
      }
    }
  }
  const std::string dir = directory_of(path);
  std::error_code ec;
  if (!dir.empty() && !std::filesystem::is_directory(dir, ec)) return write_error(path, ENOENT, "mesh");

  // Write under a temporary name with the same extension, then rename: no half-written mesh
  // ever appears under the real name.
  const std::string tmp = dir + ".tmp" + std::to_string(::getpid()) + "-" + path.substr(dir.size());
  VtkMessages messages;
  vtkSmartPointer<vtkPolyData> poly = to_vtk_poly_data(mesh);
  const unsigned long code = write_with(ext, tmp, poly);
  if (code != vtkErrorCode::NoError || messages.has_error()) {
    std::remove(tmp.c_str());
    const std::string why =
        messages.last_error().empty() ? std::string(vtkErrorCode::GetStringFromErrorCode(code)) : messages.last_error();
    if (code == vtkErrorCode::OutOfDiskSpaceError)
      return resource_exhausted("cannot write mesh '" + path + "': " + why);
    return internal_error("cannot write mesh '" + path + "': " + why);
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    std::remove(tmp.c_str());
    return write_error(path, err, "mesh");
  }
  return ok_status();
}

}  // namespace soiq
