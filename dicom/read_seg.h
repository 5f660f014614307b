#pragma once
// A binary DICOM Segmentation read back as plain structs: each segment's voxels on a given image
// grid, with what the object references. The inverse of write_seg (dicom/seg_export.h), and how
// SEGs from other tools come into soiq.
//
// Inputs   path: a Part 10 file or bare dataset. There is no in-memory form: DCMTK checks an
//          element's length against a file's size but not against a memory buffer's, where it
//          allocates whatever a hostile header claims, so bytes go to a private temp file first.
//          grid: the image grid to map frames onto, normally the referenced series' geometry.
// Output   SegObject: identity and references (Referenced Series Sequence, or the per-frame Source
//          Images when it is absent) and one ReadSegment per Segment Sequence item in file order.
//          A frame goes to slice k of grid when its Plane Position (Patient) p has continuous index
//          physical_to_index(p) = (0, 0, k) within max(0.01 mm, 1% of the spacing) on each axis
//          (the tolerance slice_stack allows between slices), its Plane Orientation equals grid's
//          direction columns i and j to 1e-4, its Pixel Spacing (when given) equals
//          spacing_mm[1]\spacing_mm[0] to 1e-4 relative, and Rows x Columns = dims[1] x dims[0].
//          Voxel (i, j, k) is inside iff pixel (row j, column i) of a frame of that segment on
//          slice k is set; two frames of one segment on one slice are united. Frame f's pixels are
//          bits f x rows x columns onwards of the whole Pixel Data, LSB first (PS3.5 8.1.1 / 8.2,
//          seg_bit_packing.h): frames need not start on a byte. DCMTK reads everything else.
// Errors   NOT_FOUND: no such file. DATA_LOSS: a file DCMTK cannot parse.
//          INVALID_ARGUMENT: not a Segmentation (names the file and its SOP class); checked before
//          any pixel is read, naming the SEG ("SEG '<path>'"): a FRACTIONAL segmentation or Bits
//          Allocated other than 1; Rows or Columns absent or 0; NumberOfFrames absent, below 1, or
//          more pixels than a Pixel Data holds (8 x (2^32 - 2)); no Pixel Data; Pixel Data shorter
//          than ceil(frames x rows x columns / 8) ("SEG 'x' is truncated: N bytes of pixel data,
//          NumberOfFrames F x Rows R x Columns C needs M"); a Per-Frame Functional Groups item count
//          other than NumberOfFrames; an invalid grid; a frame without position, orientation or
//          segment number, or one that does not fit grid (message names the frame, from 1, and what
//          differs). UNIMPLEMENTED or DATA_LOSS: compressed Pixel Data that soiq cannot decode
//          (decompress_pixels.h).
// Cost     O(frames x rows x columns + lines of grid) per segment; memory: the file, one slice
//          and the segments' runs. Thread-safe.
// Caveats  grid carries no Frame of Reference: the caller checks SegObject.frame_of_reference_uid
//          against the series'. FRACTIONAL SEGs and concatenations are not read.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"

namespace soiq::dicom {

struct SegFrameSource {
  int64_t k = 0;                        // the slice of grid the frame was mapped to
  std::string source_sop_instance_uid;  // its Derivation Image's Source Image, "" when absent
  bool operator==(const SegFrameSource&) const = default;
};

struct ReadSegment {
  int32_t segment_number = 0;  // from 1
  std::string label;
  std::string algorithm_type;  // "MANUAL", "SEMIAUTOMATIC", "AUTOMATIC"
  std::string algorithm_name;
  std::string category_code, type_code;  // "<scheme>:<value>", e.g. "SCT:85756007"
  RunLengthVolume volume;                // on grid
  std::vector<SegFrameSource> frames;    // in file order
};

struct SegObject {
  std::string sop_instance_uid, series_uid, study_uid, patient_id, frame_of_reference_uid;
  std::string referenced_series_uid;
  std::vector<std::string> referenced_sop_instance_uids;  // in file order
  std::vector<ReadSegment> segments;
};

Result<SegObject> read_seg_file(const std::string& path, const ImageGeometry& grid);

}  // namespace soiq::dicom
