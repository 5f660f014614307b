#pragma once
// The ROIs and contours of a DICOM RT Structure Set (docs/DESIGN.md "DICOM and PACS": 3006,0020
// Structure Set ROI Sequence / 3006,0039 ROI Contour Sequence / 3006,0050 Contour Data), and what
// it says about the image series it was drawn on.
//
// Inputs   path: an RTSTRUCT file, with or without preamble and file meta header.
// Output   RtStructureSet: one RtRoi per Structure Set ROI item (in file order), with its
//          CLOSED_PLANAR contours as PlanarContour in LPS mm exactly as stored (the last point
//          joins the first). Contours of other geometric types (POINT, OPEN_PLANAR,
//          OPEN_NONPLANAR) are counted per ROI in `other_contours`, not returned.
//          referenced_series_uids: RT Referenced Series of the Referenced Frame of Reference
//          Sequence; referenced_image_uids: every Referenced SOP Instance UID of a Contour Image
//          Sequence (of the referenced series and of each contour), deduplicated, in file order.
// Errors   NOT_FOUND missing file; DATA_LOSS unreadable file; INVALID_ARGUMENT when the file is
//          not an RTSTRUCT (Modality), or a CLOSED_PLANAR contour's Contour Data is not a
//          multiple of 3 numbers or holds a non-number (message names the ROI and contour).
// Cost     O(file size); thread-safe.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "core/voxelize/fill_contours.h"

namespace soiq::dicom {

struct RtRoi {
  int64_t number = 0;                   // ROI Number (3006,0022)
  std::string name;                     // ROI Name (3006,0026)
  std::string frame_of_reference_uid;   // Referenced Frame of Reference UID (3006,0024)
  std::vector<PlanarContour> contours;  // CLOSED_PLANAR only
  int64_t other_contours = 0;           // POINT and other non-CLOSED_PLANAR contours
  std::string other_types;              // their geometric types, e.g. "POINT"
};

struct RtStructureSet {
  std::string path;
  std::string sop_instance_uid;
  std::string series_uid;
  std::string study_uid;
  std::string patient_id;
  std::string label;  // Structure Set Label (3006,0002)
  std::vector<std::string> frame_of_reference_uids;
  std::vector<std::string> referenced_series_uids;
  std::vector<std::string> referenced_image_uids;
  std::vector<RtRoi> rois;
};

Result<RtStructureSet> read_rt_struct(const std::string& path);

}  // namespace soiq::dicom
