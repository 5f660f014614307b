#pragma once
// Structures as a DICOM RT Structure Set (PS3.3 A.19) on the image series they were converted on:
// the object treatment planning systems and RT tools read, beside the SEG (seg_export.h).
//
// Inputs   source: the referenced image series as soiq stored it at import (seg_export.h's
//          SegSource: the same facts describe the series for either object; no file is read).
//          rois: one per structure, each with its planar contours on slices of source.geometry
//          (core/geometry/slice_sections.h cuts them from a surface). options: what identifies
//          the new object.
// Output   WrittenRtStruct: a DICOM Part 10 file (Explicit VR Little Endian) of the RT Structure
//          Set Storage SOP class, with the source's Patient, Study and Frame of Reference, a new
//          Series and SOP Instance UID (dcmGenerateUniqueIdentifier unless options give them) and:
//          Structure Set: Referenced Frame of Reference -> RT Referenced Study (the study) -> RT
//          Referenced Series (the series) -> Contour Image Sequence listing every slice of the
//          series; Structure Set ROI n (from 1) = rois[n-1], its name and generation algorithm.
//          ROI Contour: per ROI its ROI Display Color and one CLOSED_PLANAR contour per section
//          polygon (holes and separate parts are separate contours, PS3.3 C.8.8.6, read under
//          even-odd), each with a Contour Image Sequence naming the slice of its plane (SOP Class
//          and Instance UID), its points as Contour Data (DS, format_ds below).
//          RT ROI Observations: one per ROI, RT ROI Interpreted Type as given ("" = unknown).
//          The Type 2 values of Patient and Study are copied when they fit their VR, else empty.
// Errors   INVALID_ARGUMENT, naming the ROI or field: an invalid source geometry, slice uid count
//          != dims[2], an empty study/series/frame of reference/SOP class uid, no ROIs, an empty
//          or non-LO name, a contour with fewer than 3 points or non-finite ones, a contour on a
//          slice outside the grid, an interpreted type or algorithm DICOM does not define.
//          FAILED_PRECONDITION: an ROI with no contour (a structure between the series' planes).
//          RESOURCE_EXHAUSTED over options.max_points points in all. INTERNAL when DCMTK refuses
//          the object (its text kept).
// Cost     O(points) to format and encode. Thread-safe.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/base/status.h"
#include "core/geometry/slice_sections.h"
#include "dicom/seg_export.h"

namespace soiq::dicom {

struct RtStructRoi {
  std::string name;                                    // ROI Name (LO); non-empty
  std::vector<SliceSection> contours;                  // on slices of the source grid
  std::array<uint8_t, 3> display_rgb{};                // ROI Display Color
  std::string interpreted_type;                        // RT ROI Interpreted Type: "", "GTV", "ORGAN", ...
  std::string generation_algorithm = "SEMIAUTOMATIC";  // AUTOMATIC, SEMIAUTOMATIC or MANUAL
};

struct RtStructWriteOptions {
  std::string series_uid;        // "" -> a new one
  std::string sop_instance_uid;  // "" -> a new one
  std::string series_description = "soiq structure set";
  int32_t series_number = 901;
  std::string label = "SOIQ";  // Structure Set Label (SH)
  // Structure Set Date and Time (DA, TM); "" -> now. Fixed values make the same object written
  // twice the same bytes (DICOMweb's stable objects).
  std::string date, time;
  int64_t max_points = 20'000'000;
};

struct WrittenRtStruct {
  std::string bytes;  // the Part 10 file
  std::string series_uid, sop_instance_uid;
  int64_t contour_count = 0, point_count = 0;
};

Result<WrittenRtStruct> write_rt_struct(const SegSource& source, const std::vector<RtStructRoi>& rois,
                                        const RtStructWriteOptions& options = {});

// A coordinate as a DICOM DS value (at most 16 characters): the shortest "%.Ng" that reads back
// to the same double, else the most significant digits that fit. In millimetres below 1000 that
// keeps at least 11 decimals (e.g. "-999.99999999999"): a point moves by at most 5e-12 mm, so
// only a voxel centre within that distance of a contour can change side when read back.
std::string format_ds(double value);

}  // namespace soiq::dicom
