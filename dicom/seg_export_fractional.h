#pragma once
// Structures' coverage fractions (docs/DESIGN.md "Coverage fractions") as a FRACTIONAL DICOM
// Segmentation of type OCCUPANCY: each pixel the fraction of its voxel's volume inside the
// structure. Opt-in beside write_seg's binary SEG (seg_export.h), which stays the default since
// OHIF and dcmqi read only binary SEGs; highdicom and pydicom read fractional ones.
//
// Inputs   source: as write_seg. segments: one per structure, each a CoverageVolume on
//          source.geometry. options: as write_seg.
// Output   WrittenSeg: as write_seg's object (same modules, UIDs chosen the same way, the same
//          per-frame and shared functional groups, dimension index and references), except that
//          SegmentationType is FRACTIONAL, SegmentationFractionalType OCCUPANCY, Maximum Fractional
//          Value 255, Bits Allocated = Bits Stored = 8, High Bit 7, and each frame holds one byte per
//          pixel: 0 for a voxel wholly outside, 255 for one wholly inside and fraction_byte(f) (1..254)
//          for one partly covered, as to_fraction_bytes gives them. A frame per (segment, slice k)
//          that holds a voxel with any coverage, ordered by segment then k.
// Errors   write_seg's INVALID_ARGUMENT, RESOURCE_EXHAUSTED (here rows x columns bytes per frame)
//          and INTERNAL; INVALID_ARGUMENT for a coverage volume whose index arrays have the wrong
//          size, and "structure 'X' has no voxels" for one with no coverage at all.
// Cost     O(segments x slices x rows x columns). Thread-safe as write_seg.
// Caveats  soiq reads back only binary SEGs (read_seg.h refuses FRACTIONAL ones): a fractional SEG
//          is for other readers.

#include <cstdint>
#include <vector>

#include "core/base/coverage_volume.h"
#include "core/base/status.h"
#include "dicom/seg_export.h"

namespace soiq::dicom {

struct FractionalSegSegment : SegSegmentDescription {
  CoverageVolume coverage;  // on source.geometry
};

// Maximum Fractional Value: the byte of a voxel wholly inside.
inline constexpr int kSegMaxFractionalValue = 255;

Result<WrittenSeg> write_fractional_seg(const SegSource& source, const std::vector<FractionalSegSegment>& segments,
                                        const SegWriteOptions& options = {});

// What write_fractional_seg holds at its peak, to admit it against a memory budget: the frames'
// bytes three times (DCMTK's copy, the dataset's Pixel Data, the Part 10 bytes), one frame, and
// DCMTK's functional-group items per frame (4 KiB counted).
int64_t fractional_seg_write_peak_bytes(const ImageGeometry& geometry,
                                        const std::vector<FractionalSegSegment>& segments);

}  // namespace soiq::dicom
