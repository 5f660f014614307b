#pragma once
// The records the store keeps, as plain structs (docs/DESIGN.md "Storage"): a patient, a study, an image
// series, a structure with its surface's facts. The Store (store.h) reads and writes them; every
// layer above speaks them.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"

namespace soiq::db {

struct PatientRecord {
  std::string patient_id;
  std::string sex;         // "M", "F", "O" or ""
  std::string birth_date;  // YYYYMMDD or ""
  // DICOM Patient's Name (0010,0010) in UTF-8, "^" between components; "" when unknown or not kept
  // (soiqd keeps names only when started with --keep-patient-names). Never logged.
  std::string patient_name;
  int64_t study_count = 0;      // filled on reads
  int64_t structure_count = 0;  // filled on reads
};

struct StudyRecord {
  std::string study_uid;
  std::string patient_id;
  std::string study_date;  // YYYYMMDD or ""
  // DICOM Study Time (0008,0030), Study ID (0020,0010) and Accession Number (0008,0050) as
  // imported, "" when unknown: a SEG soiq writes on the study repeats them (dicom/seg_export.h), so
  // a PACS and a RIS file it with its study.
  std::string study_time;
  std::string study_id;
  std::string accession_number;
  std::string description;
  std::string modality;  // the study's own modality, may be ""
  // Given (DICOM Patient's Age) or, when absent, computed by the store from birth and study date.
  std::optional<double> age_years;
  int64_t structure_count = 0;  // filled on reads
};

struct SeriesRecord {
  std::string series_uid;
  std::string study_uid;
  std::string modality;
  ImageGeometry geometry;
  std::string sha256;  // of the image blob
  // DICOM references, for writing objects derived from the series (DICOM SEG); "" and empty for
  // series that did not come from DICOM.
  std::string frame_of_reference_uid;
  std::string sop_class_uid;                     // of its slices
  std::vector<std::string> slice_instance_uids;  // SOP Instance UID of slice k, by k
  int64_t series_number = 0;                     // (0020,0011), 0 when unknown
  std::string description;                       // (0008,103E), "" when unknown
  // The first Window Center/Width (0028,1050/1051) of its slices, in the stored voxels' units: how
  // the modality's reader meant it shown (pictures start from it). Width 0: none (an upload, a PET
  // series whose voxels became SUV, or a store from before these were kept).
  double window_center = 0;
  double window_width = 0;
};

// An original DICOM instance of an image series, kept as it was received (soiqd --keep-instances,
// on by default): what WADO-RS serves, so that a viewer opens the series from soiq alone and the
// SEGs soiq writes resolve against the SOP Instance UIDs they reference. The file is stored once
// per sha256 however many instances (a re-sent file) name it.
struct InstanceRecord {
  std::string sop_instance_uid;
  std::string series_uid;
  int64_t slice = 0;        // the slice k of the series it holds (its first frame's, for multi-frame)
  std::string file_sha256;  // of the Part 10 file as received, lower-case hex: its key
  int64_t file_bytes = 0;   // the file's size
  std::string metadata;     // the DICOM JSON Model (PS3.18 F.2) of its attributes, bulk data left out
};

struct SurfaceInfo {
  std::string sha256;  // of the canonical (uncompressed) encoding
  int64_t vertex_count = 0;
  int64_t triangle_count = 0;
  double bounds_mm[6] = {0, 0, 0, 0, 0, 0};
  // surface_measure's bounds (core/voxelize/memory_estimate.h), kept (with each structure) so a
  // conversion's memory can be budgeted without decoding and walking the surface first. 0 and 0:
  // unknown (admission measures the mesh).
  double area_bound_mm2 = 0;
  double perimeter_bound_mm = 0;
};

struct StructureRecord {
  int64_t id = 0;
  std::string patient_id;
  std::string study_uid;
  std::string name;
  std::string laterality;  // "L", "R" or ""
  bool robust = false;
  std::string created_at;  // ISO 8601 UTC, set by the store
  SurfaceInfo surface;
  // Where an imported structure came from; "" for uploads. source_series_uid: the image series
  // whose grid its volume was converted on (DICOM SEG export writes on it). source_uid: the
  // RT Structure Set's SOP Instance UID + "/" + the ROI number, unique in the store, so importing
  // the same structure set again updates its structures instead of adding copies.
  std::string source_series_uid;
  std::string source_uid;
};

}  // namespace soiq::db
