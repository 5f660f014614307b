#pragma once
// Everything soiq takes from a set of DICOM files, ready to store (issue 5 deliverable 1): the
// records of dicom/scan_dicom.h, each CT, MR and PET series as an image (read_image_series.h),
// each RT Structure Set converted on its referenced series' grid (referenced_series.h,
// convert_rt_struct.h), and each binary DICOM Segmentation read on its referenced series' grid
// (import_seg.h; its segments become structures like ROIs). The store is the caller's business
// (db/), this module only reads.
//
// Inputs   paths: files, folders and DICOMDIRs as scan_dicom takes them.
//          max_voxels: per image and per structure grid (RESOURCE_EXHAUSTED beyond).
// Output   DicomImport. A series or structure set that cannot be used does not stop the import:
//          it goes to `problems` with its Status (the message names the file, series or uid),
//          e.g. a missing slice (INVALID_ARGUMENT), a structure set whose referenced series is
//          not among the files (NOT_FOUND naming it). Series of other modalities (CR, DX, SR,
//          ...) stay in the scan's records only.
// Errors   NOT_FOUND when a path does not exist.
// Cost     O(files + voxels + contour points); single-threaded.

#include <string>
#include <vector>

#include "core/status.h"
#include "dicom/convert_rt_struct.h"
#include "dicom/read_image_series.h"
#include "dicom/records.h"

namespace soiq::dicom {

// An RT Structure Set or a DICOM SEG (then roi_number is the Segment Number and label the SEG's
// Series Description).
struct ImportedStructureSet {
  std::string path;
  std::string sop_instance_uid;
  std::string series_uid;
  std::string study_uid;
  std::string patient_id;
  std::string label;
  std::string referenced_series_uid;  // the image series the volumes are on
  ConvertedStructureSet converted;
  bool segmentation = false;  // a DICOM SEG: its "ROIs" are segments
};

struct DicomImport {
  DicomScan scan;
  std::vector<SeriesImage> images;
  std::vector<ImportedStructureSet> structure_sets;
  std::vector<FileProblem> problems;  // path: the file or, for a whole series, its uid

  const SeriesImage* find_image(const std::string& series_uid) const;  // nullptr when absent
};

// True for the modalities imported as volumes: CT, MR, PT.
bool is_volume_modality(const std::string& modality);

Result<DicomImport> import_dicom(const std::vector<std::string>& paths, int64_t max_voxels = kDefaultMaxVoxels);

}  // namespace soiq::dicom
