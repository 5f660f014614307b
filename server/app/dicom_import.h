#pragma once
// A folder of received DICOM files -> stored series and structures (the ImportDicom
// RPC). Reads everything with dicom::import_dicom, converts and encodes it all first,
// then writes it with Store::import_batch in one transaction: an import that fails stores nothing.
//
// Inputs   dir: the folder the files were received into (server/api/received_dicom_files.h); sent:
//          their relative paths; max_voxels: per image and per structure grid. budget: the
//          images' peak bytes (server/app/dicom_import_bytes.h, from the headers) are reserved there
//          after the header scan and before any pixel is decoded, and held until the write is
//          done; while others hold the budget the import waits, first come first served, until
//          `stop` returns non-OK, which is asked once more just before the write (a client that
//          gave up gets nothing stored). Call on a worker (as FeatureEngine::admit).
// Output   What was imported (the api layer turns it into ImportDicom's reply, proto_records.h):
//          - series: each CT, MR and PET series as an image, in its DICOM study and patient
//            (sex, birth and study dates kept when valid, age at study from dicom/; no names);
//          - structures: one per RT Structure Set ROI with a non-empty volume, named as the ROI,
//            in the study of the series it references (so features on "CT" or "PT" of that study
//            use the images it was drawn on); laterality "L" or "R" only when the name ends in
//            "_L", " L", "_R" or " R" (upper case), else "". The surface is the marching-cubes
//            surface of the ROI's volume on the referenced grid;
//          - structures also from each binary DICOM SEG, one per non-empty segment, named by its
//            Segment Label, on the series it references (dicom/import_seg.h). Importing the same
//            SEG again updates its structures in place (source uid = SEG SOP Instance UID /
//            segment number). A segment with the same study, series, name and voxels as a stored
//            structure is that structure, recognised, not stored twice: so a SEG soiq exported
//            (ExportSeg, PacsPush) and pulled back, any number of times, adds nothing; the
//            response lists the stored structure (its id, its original source uid) with
//            replaced = true. Edited voxels or a new label make it a new structure;
//          - series and study records keep Study Time, Study ID and Accession Number (when at
//            most 64 characters without control characters) for the SEGs exported on them;
//          - a structure set or SEG whose series is not among the files but already stored is
//            converted on the stored series' grid and filed in its study (same patient and frame
//            of reference required, else a problem);
//          - problems: unreadable files, unusable series, skipped or empty ROIs, non-DICOM files,
//            with paths relative to `dir`.
// Errors   INVALID_ARGUMENT when nothing at all can be imported (the message names the first
//          problem or file). RESOURCE_EXHAUSTED when the images can never fit the budget (the
//          message names the series, the estimate and the limit), before anything is decoded or
//          stored. `stop`'s status when it ends a wait or the import. Any Store error unchanged (nothing stored
//          then).
// Cost     O(files + voxels + contour points) reads, then one write transaction.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/memory_budget.h"

namespace soiq::server {

// A file, series or ROI that was skipped; `path` relative to the folder ("" for the whole import).
struct ImportProblem {
  std::string path;
  StatusCode code = StatusCode::kInvalidArgument;
  std::string message;
};

struct ImportedStructure {
  db::StructureRecord structure;
  std::string referenced_series_uid;  // the grid its volume was converted on
  int64_t voxel_count = 0;            // voxels inside on that grid
  bool replaced = false;              // an earlier import's structure, updated or recognised
};

struct DicomImportResult {
  std::vector<db::PatientRecord> patients;  // by patient id
  std::vector<db::StudyRecord> studies;     // by study uid
  std::vector<db::SeriesRecord> series;
  std::vector<ImportedStructure> structures;
  std::vector<ImportProblem> problems;
  // RT Structure Sets and SEGs sent from which no structure was stored (every ROI refused or
  // skipped, or the file refused whole): the import did not do what it was asked.
  std::vector<std::string> structure_sets_without_structures;
  int64_t files_received = 0;
  int64_t dicom_files_read = 0;
  double milliseconds = 0;
};

struct DicomImportOptions {
  bool keep_patient_names = false;  // soiqd --keep-patient-names
  bool replace = false;             // soiq import --replace: a UID stored with other content is replaced
  // soiqd --keep-instances: each image series' original files are stored with it
  // (server/app/kept_instances.h), for WADO-RS.
  bool keep_instances = true;
};

Result<DicomImportResult> import_dicom_folder(db::RecordStore& store, const std::string& dir,
                                              const std::vector<std::string>& sent, int64_t max_voxels,
                                              MemoryBudget& budget, const std::function<Status()>& stop,
                                              const DicomImportOptions& options = {});

}  // namespace soiq::server
