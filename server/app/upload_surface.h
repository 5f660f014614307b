#pragma once
// An uploaded surface model stored as a new structure (the UploadSurface RPC, docs/DESIGN.md
// "Untrusted input"): the bytes parsed in memory by parse_surface (uploaded_files.h), encoded and
// stored with its patient and study in one transaction.
//
// Inputs   upload: the header's fields, already checked by the caller (patient and study
//          records, a non-empty name, laterality L, R or empty); `format` is the file format
//          (stl, obj, ply, off, vtk, vtp), `ras` flips x and y into LPS, `robust` admits an open
//          surface. bytes: the file, whole, at most the caller's upload limit.
// Output   The stored structure (surface_already_stored when the same surface was stored before)
//          and the defects of the parsed mesh.
// Errors   parse_surface's: INVALID_ARGUMENT for an unknown format, empty or malformed bytes;
//          FAILED_PRECONDITION for an open surface without robust. The store's: FAILED_PRECONDITION
//          for a study stored under another patient, INVALID_ARGUMENT for a record it refuses.
//          Nothing is stored on any error.
// Cost     O(bytes + triangles); thread-safe as the Store is.

#include <string>

#include "core/base/status.h"
#include "core/geometry/mesh_defects.h"
#include "db/store.h"

namespace soiq::server {

struct SurfaceUpload {
  db::PatientRecord patient;
  db::StudyRecord study;
  std::string structure_name;
  std::string laterality;
  std::string format;
  bool ras = false;
  bool robust = false;
};

struct UploadedSurface {
  db::AddedStructure added;
  MeshDefects defects;
};

Result<UploadedSurface> upload_surface(db::RecordStore& store, const SurfaceUpload& upload, const std::string& bytes);

}  // namespace soiq::server
