#pragma once
// Structures as a binary DICOM Segmentation (docs/DESIGN.md "DICOM and PACS": the object soiq C-STOREs
// back to a PACS), on the grid of the image series they were converted on.
//
// Inputs   source: the referenced image series as soiq stored it at import (no file is read).
//          segments: one per structure, each volume on source.geometry (any orientation, oblique
//          included). options: what identifies the new object.
// Output   WrittenSeg: a DICOM Part 10 file (Explicit VR Little Endian) of the Segmentation
//          Storage SOP class, SegmentationType BINARY, with the source's Patient, Study and Frame of
//          Reference and a new Series and SOP Instance UID (dcmGenerateUniqueIdentifier unless
//          options give them). Segment n (from 1) is segments[n-1]: label, category and type codes,
//          algorithm type and name, optional colour (as CIELab). Frames are sparse: one frame per
//          (segment, slice k) that holds a voxel of that segment, ordered by segment then k; each
//          frame has rows x columns = dims[1] x dims[0], pixel (r, c) = voxel (i=c, j=r, k), and per
//          frame Plane Position (Patient) = index_to_physical(0,0,k), Frame Content dimension
//          values (segment number, k + 1) and a Derivation Image item whose Source Image is slice
//          k's SOP instance (purpose 121322 DCM "Source image for image processing operation").
//          Shared: Plane Orientation (Patient) = direction columns i and j, Pixel Measures (Pixel
//          Spacing = spacing_mm[1]\spacing_mm[0], Slice Thickness = Spacing Between Slices =
//          spacing_mm[2]). The Referenced Series Sequence lists the slices that frames derive from.
//          Pixel Data holds the frames' bits back to back, LSB first, as PS3.5 8.1.1 / 8.2 say
//          (seg_bit_packing.h, not DCMTK's packing): ceil(rows x columns x frames / 8) bytes,
//          padded to an even length. The Type 2 values Patient's Sex and Birth Date, Study Date,
//          Time, ID and Accession Number are the source's when they fit their VR, else present and
//          empty (never truncated: a 17-character Study ID is written empty).
// Errors   INVALID_ARGUMENT, naming the segment or field: an invalid source geometry, dims[0] or
//          dims[1] over 65535, slice uid count != dims[2], an empty study/series/frame of
//          reference/SOP class uid, no segments, an empty label, no algorithm name unless MANUAL, a
//          segment volume whose geometry differs from source.geometry or whose line_start has the
//          wrong size, a segment with no voxels ("structure 'X' has no voxels"). RESOURCE_EXHAUSTED over
//          options.max_frames frames or 2^32 - 2 bytes of pixel data. INTERNAL when DCMTK refuses the
//          object (its text kept).
// Cost     O(segments x slices x rows x columns) to build the frames, plus DCMTK's functional
//          group handling (linear in frames). Thread-safe: no shared state besides DCMTK's logger.
// Caveats  Writes one instance (no concatenation). Frames of empty slices are left out: Part 3
//          does not ask for a frame per source slice, and readers (DCMTK, dcmqi, viewers) place
//          frames by their Plane Position, so a GTV on 20 of 300 slices costs 20 frames, not 300.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"

namespace soiq::dicom {

// The referenced image series, as soiq stored it at import.
struct SegSource {
  std::string patient_id;          // (0010,0020)
  std::string patient_name;        // (0010,0010), may be empty (kept only with --keep-patient-names)
  std::string patient_sex;         // (0010,0040) "M", "F", "O" or ""
  std::string patient_birth_date;  // (0010,0030) YYYYMMDD or ""
  std::string study_uid;           // (0020,000D)
  std::string study_date;          // (0008,0020) YYYYMMDD or ""
  std::string study_time;          // (0008,0030) or ""
  std::string study_id;            // (0020,0010) or ""
  std::string accession_number;    // (0008,0050) or ""
  std::string series_uid;          // (0020,000E) of the image series
  std::string frame_of_reference_uid;
  std::string modality;                              // of the image series, e.g. "CT"
  std::string sop_class_uid;                         // of the image slices
  std::vector<std::string> slice_sop_instance_uids;  // by k, as read_image_series gives them
  ImageGeometry geometry;                            // the series' grid (LPS)
};

// A code of DICOM Part 16 (Code Value, Coding Scheme Designator, Code Meaning).
struct SegCode {
  std::string value, scheme, meaning;
  bool operator==(const SegCode&) const = default;
};

// SCT 85756007 "Tissue": the generic category and type (CID 7150 / 7151) for a structure whose
// anatomy soiq does not know. A caller that knows better passes e.g. SCT 49755003 "Morphologically
// Altered Structure" / SCT 4147007 "Mass" for a GTV.
inline const SegCode kTissueCode{"85756007", "SCT", "Tissue"};

enum class SegAlgorithmType { kManual, kSemiautomatic, kAutomatic };

// What a segment is, whatever its voxels (binary here, fractional in seg_export_fractional.h).
struct SegSegmentDescription {
  std::string label;  // Segment Label: the structure's name; non-empty
  SegCode category = kTissueCode;
  SegCode type = kTissueCode;
  // SEMIAUTOMATIC by default: an RT structure's outline is drawn by a person, which voxels it holds
  // is soiq's rule (voxel centre inside, even-odd); AUTOMATIC fits model output, MANUAL painted masks.
  SegAlgorithmType algorithm_type = SegAlgorithmType::kSemiautomatic;
  std::string algorithm_name = "soiq";                // required unless MANUAL
  std::optional<std::array<uint8_t, 3>> display_rgb;  // Recommended Display CIELab Value from sRGB
};

struct SegSegment : SegSegmentDescription {
  RunLengthVolume volume;  // on source.geometry
};

struct SegWriteOptions {
  std::string series_uid;        // "" -> a new one
  std::string sop_instance_uid;  // "" -> a new one
  std::string series_description = "soiq segmentation";
  int32_t series_number = 900;
  std::string content_label = "SOIQ";  // CS: upper case, <= 16 characters
  std::string content_description;
  int64_t max_frames = 100'000;
  // What makes the same SEG written twice the same bytes (DICOMweb's stable SEGs): the Dimension
  // Organization UID ("" -> a new one) and Content Date and Time (DA, TM; "" -> now).
  std::string dimension_organization_uid;
  std::string content_date, content_time;
};

struct WrittenSeg {
  std::string bytes;  // the Part 10 file
  std::string series_uid, sop_instance_uid;
  int64_t frame_count = 0;
};

Result<WrittenSeg> write_seg(const SegSource& source, const std::vector<SegSegment>& segments,
                             const SegWriteOptions& options = {});

// What write_seg holds at its peak for `segments` on `geometry`, to admit it against a memory
// budget: the frames' packed bits three times (packed, in the dataset, in the Part 10 bytes), one
// unpacked frame, and DCMTK's functional-group items per frame (4 KiB counted).
int64_t seg_write_peak_bytes(const ImageGeometry& geometry, const std::vector<SegSegment>& segments);

}  // namespace soiq::dicom
