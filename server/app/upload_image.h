#pragma once
// An uploaded image stored as a series (the UploadImage RPC, docs/DESIGN.md "Untrusted input"): the
// bytes parsed in memory by parse_image (uploaded_files.h), encoded and stored with its patient
// and study in one transaction. The decoded image and its encoded blob are admitted against the
// memory budget as soon as the file's header tells their size, before a voxel is decoded, and
// held until the series is stored.
//
// Inputs   upload: the header's fields, already checked by the caller (patient and study
//          records, non-empty series_uid and modality); `format` is nii, nii.gz, nrrd or mha.
//          bytes: the file, whole, at most the caller's upload limit. budget: the server's memory
//          budget. max_grid_voxels: the largest image accepted. stop: CANCELLED or
//          DEADLINE_EXCEEDED once the caller is gone (polled while waiting for the budget, and
//          once more just before the write).
// Output   The stored series record (its geometry and sha256 filled) and whether it replaced a
//          stored series of the same uid.
// Errors   parse_image's: INVALID_ARGUMENT for an unknown format, empty or malformed bytes or a
//          header naming a data file; RESOURCE_EXHAUSTED for a grid over max_grid_voxels or an
//          image that can never fit the budget (naming the series and its size); stop's status.
//          The store's: FAILED_PRECONDITION for a study or series stored under another patient.
//          Nothing is stored, and nothing stays reserved, on any error.
// Cost     O(bytes + voxels); thread-safe as the Store and the budget are.

#include <cstdint>
#include <functional>
#include <string>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/memory_budget.h"

namespace soiq::server {

struct ImageUpload {
  db::PatientRecord patient;
  db::StudyRecord study;
  std::string series_uid;
  std::string modality;
  std::string format;
};

struct UploadedImage {
  db::SeriesRecord series;
  bool replaced = false;
};

Result<UploadedImage> upload_image(db::RecordStore& store, MemoryBudget& budget, int64_t max_grid_voxels,
                                   const ImageUpload& upload, const std::string& bytes,
                                   const std::function<Status()>& stop);

}  // namespace soiq::server
