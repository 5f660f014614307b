#pragma once
// Internal to dicom/seg_export*.cpp, not part of write_seg's interface (seg_export.h): the steps
// write_seg and write_fractional_seg build a DICOM SEG with, shared between the files that hold
// them. seg_export.cpp checks the inputs, creates the object and encodes it;
// seg_export_modules.cpp fills in its modules (identity, segment descriptions, references);
// seg_export_frames.cpp adds its frames (functional groups and pixels); seg_export_fractional.cpp
// does the fractional object's own steps. Includes DCMTK, which the public headers of dicom/ never do.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmseg/segdoc.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "dicom/seg_bit_packing.h"
#include "dicom/seg_export.h"

namespace soiq::dicom {

// seg_export.cpp: INTERNAL "DICOM SEG: <what> (<DCMTK's text>)", for a step DCMTK refused.
Status seg_export_error(const std::string& what, const OFCondition& cond);
// seg_export.cpp: a new UID under `root` (dcmGenerateUniqueIdentifier).
std::string new_uid(const char* root);

// seg_export.cpp: the checks of write_seg's interface that do not depend on how a segment's voxels
// are held: the source series, and segment `number` (from 1) whose voxels are on `volume_grid`.
Status check_seg_source(const SegSource& source);
Status check_segment(const SegSegmentDescription& s, size_t number, const ImageGeometry& volume_grid,
                     const ImageGeometry& source_grid);
// seg_export.cpp: RESOURCE_EXHAUSTED over options.max_frames frames or DICOM's 32-bit Pixel Data.
Status check_seg_size(int64_t frames, int64_t pixel_data_bytes, const SegWriteOptions& options);
// seg_export.cpp: DCMTK's IOD checks log to stderr; what matters comes back as a Status.
void quiet_dcmtk_seg_logs();
// seg_export.cpp: a new SEG of source's rows and columns: binary when max_fractional_value is 0,
// else FRACTIONAL OCCUPANCY with that Maximum Fractional Value.
Result<std::unique_ptr<DcmSegmentation>> create_seg(const SegSource& source, const SegWriteOptions& options,
                                                    Uint16 max_fractional_value);
// seg_export.cpp: the new object's identity, its segments and shared functional groups (before the
// frames), with out.series_uid and out.sop_instance_uid chosen.
Status describe_seg(DcmSegmentation& seg, const SegSource& source,
                    const std::vector<const SegSegmentDescription*>& segments, const SegWriteOptions& options,
                    WrittenSeg& out);
// seg_export.cpp: the object as Part 10 bytes into out.bytes (and out.frame_count), with Specific
// Character Set when a text is beyond ASCII and the options' content date; `pixels`, when given,
// replaces the Pixel Data DCMTK wrote (binary frames, put_pixel_data).
Status encode_seg(DcmSegmentation& seg, const SegSource& source,
                  const std::vector<const SegSegmentDescription*>& segments, const SegWriteOptions& options,
                  const BinaryFramePacker* pixels, WrittenSeg& out);

// seg_export_modules.cpp: Patient, General Study, Frame of Reference, Series and SOP Common of the
// new object, with the Type 2 values that do not fit their VR left empty. INVALID_ARGUMENT when
// DCMTK refuses a value.
Status set_identity(DcmSegmentation& seg, const SegSource& src, const SegWriteOptions& options,
                    const std::string& series_uid, const std::string& sop_uid);
// seg_export_modules.cpp: one Segment Sequence item (label, codes, algorithm, colour); segments are
// numbered from 1 in the order they are added.
Status add_segment(DcmSegmentation& seg, const SegSegmentDescription& s);
// seg_export_modules.cpp: the Referenced Series Sequence, listing the slices that `slices` (the
// occupied slices of each segment) name.
Status add_references(DcmSegmentation& seg, const SegSource& src, const std::vector<std::vector<int64_t>>& slices);

// seg_export_frames.cpp: the slices k that hold at least one voxel of v, ascending: the frames of
// its segment.
std::vector<int64_t> occupied_slices(const RunLengthVolume& v);
// seg_export_frames.cpp: the functional groups every frame shares, and the dimension index.
Status add_shared_groups(DcmSegmentation& seg, const ImageGeometry& g, const std::string& organization_uid);
// seg_export_frames.cpp: the frames of segment `s` on `slices` to seg (for their functional
// groups), and their pixels to `pixels`, in the same order.
Status add_frames(DcmSegmentation& seg, const SegSource& src, const SegSegment& s, Uint16 segment_number,
                  const std::vector<int64_t>& slices, BinaryFramePacker& pixels);
// seg_export_frames.cpp: one frame of slice k of segment `segment_number` ('label'): its Plane
// Position, Frame Content and Derivation Image groups (`derivation` describes what its pixels
// are), and its rows x columns bytes as DcmSegmentation::addFrame takes them.
Status add_frame(DcmSegmentation& seg, const SegSource& src, const std::string& label, Uint16 segment_number, int64_t k,
                 const char* derivation, std::vector<Uint8>& frame);
// seg_export_frames.cpp: replaces the Pixel Data DCMTK wrote into `ds` by the frames in `pixels`.
Status put_pixel_data(DcmDataset& ds, const BinaryFramePacker& pixels);

}  // namespace soiq::dicom
