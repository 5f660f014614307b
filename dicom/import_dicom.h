#pragma once
// Everything soiq takes from a set of DICOM files, ready to store: the
// records of dicom/scan_dicom.h, each CT, MR and PET series as an image (read_image_series.h),
// each RT Structure Set converted on its referenced series' grid (referenced_series.h,
// convert_rt_struct.h), and each binary DICOM Segmentation read on its referenced series' grid
// (import_seg.h; its segments become structures like ROIs). The store is the caller's business
// (db/), this module only reads.
//
// Inputs   paths: files, folders and DICOMDIRs as scan_dicom takes them.
//          max_voxels: per image and per structure grid (RESOURCE_EXHAUSTED beyond).
//          before_decoding: called once with the scan (headers only, no pixel read yet), before
//          any series is decoded; soiqd reserves the decoding's memory there.
// Output   DicomImport. A series or structure set that cannot be used does not stop the import:
//          it goes to `problems` with its Status (the message names the file, series or uid),
//          e.g. a missing slice (INVALID_ARGUMENT), a structure set whose referenced series is
//          not among the files (NOT_FOUND naming it). Series of other modalities (CR, DX, SR,
//          ...) stay in the scan's records only.
// Errors   NOT_FOUND when a path does not exist. Whatever before_decoding returns, unchanged.
// Cost     O(files + voxels + contour points); single-threaded.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
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
  // The referenced series was not among the files but is one the caller already holds
  // (FindKnownSeries): the volumes are on its grid, its patient and study are the caller's.
  bool on_known_series = false;
};

// An image series the caller already holds (soiqd: its store), so that an RT Structure Set or a
// SEG sent without its images (drawn later, by another system) still finds its grid.
struct KnownSeries {
  std::string series_uid, study_uid, patient_id, frame_of_reference_uid;
  ImageGeometry geometry;
};
// nullopt when the caller does not hold `series_uid`.
using FindKnownSeries = std::function<std::optional<KnownSeries>(const std::string& series_uid)>;

struct DicomImport {
  DicomScan scan;
  std::vector<SeriesImage> images;
  std::vector<ImportedStructureSet> structure_sets;
  std::vector<FileProblem> problems;  // path: the file or, for a whole series, its uid
  // RT Structure Sets and SEGs that failed as a whole (their problem is in `problems`).
  std::vector<std::string> failed_structure_sets;

  const SeriesImage* find_image(const std::string& series_uid) const;  // nullptr when absent
};

// True for the modalities imported as volumes: CT, MR, PT.
bool is_volume_modality(const std::string& modality);

// Admits an import on its scan before any pixel is decoded; a non-OK status stops the import.
using BeforeDecoding = std::function<Status(const DicomScan& scan)>;

// `known`: consulted for a structure set or SEG whose referenced series (named by uid) is not among
// the files. Such a set is refused (INVALID_ARGUMENT problem) when its frame of reference or its
// patient id differs from the known series': a structure drawn on one patient's images must never
// land on another's.
Result<DicomImport> import_dicom(const std::vector<std::string>& paths, int64_t max_voxels = kDefaultMaxVoxels,
                                 const FindKnownSeries& known = {}, const BeforeDecoding& before_decoding = {});

}  // namespace soiq::dicom
