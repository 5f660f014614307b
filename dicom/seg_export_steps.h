#pragma once
// Internal to dicom/seg_export*.cpp, not part of write_seg's interface (seg_export.h): the steps
// write_seg builds a DICOM SEG with, shared between the files that hold them. seg_export.cpp checks
// the inputs, creates the object and encodes it; seg_export_modules.cpp fills in its modules
// (identity, segment descriptions, references); seg_export_frames.cpp adds its frames (functional
// groups and pixels). Includes DCMTK, which the public headers of dicom/ never do.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmseg/segdoc.h>

#include <cstdint>
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

// seg_export_modules.cpp: Patient, General Study, Frame of Reference, Series and SOP Common of the
// new object, with the Type 2 values that do not fit their VR left empty. INVALID_ARGUMENT when
// DCMTK refuses a value.
Status set_identity(DcmSegmentation& seg, const SegSource& src, const SegWriteOptions& options,
                    const std::string& series_uid, const std::string& sop_uid);
// seg_export_modules.cpp: one Segment Sequence item (label, codes, algorithm, colour); segments are
// numbered from 1 in the order they are added.
Status add_segment(DcmSegmentation& seg, const SegSegment& s);
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
// seg_export_frames.cpp: replaces the Pixel Data DCMTK wrote into `ds` by the frames in `pixels`.
Status put_pixel_data(DcmDataset& ds, const BinaryFramePacker& pixels);

}  // namespace soiq::dicom
