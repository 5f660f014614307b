#pragma once
// A DICOM Segmentation (SEG) file -> structures, the way an RT Structure Set becomes structures
// (dicom/import_dicom.h): segments from AI and segmentation tools, and the SEGs soiq itself
// exports (dicom/seg_export.h), come back in as volumes on the image series they were drawn on.
//
// Inputs   inst: a scanned instance of SOP class Segmentation Storage. scan: everything scanned
//          with it. images: the image series imported from the same files. known: series the caller
//          holds, used when the referenced series is not among `images` (then on_known_series, and
//          the SEG must have that series' patient and frame of reference, known_series_check.h).
// Output   An ImportedStructureSet: label = the SEG's Series Description; one ImportedStructure per
//          segment with at least one voxel (roi_number = Segment Number, name = Segment Label or
//          "segment N", contour_count 0, volume = read_seg's on the referenced series' grid,
//          surface = volume_surface); segments without voxels are listed in `skipped`.
//          Re-imports are the store's business: soiqd recognises a segment that repeats a stored
//          structure of its series (server/app/dicom_import.h), so soiq's own SEG coming back adds
//          no copy. The referenced series is the SEG's Referenced Series Sequence; a SEG without one
//          (allowed for single-series SEGs by some tools) falls back to the one imported image
//          series of its study with its Frame of Reference.
// Errors   NOT_FOUND naming the SEG and the series when the referenced series is not among the
//          imported images (or, without a Referenced Series Sequence, none or several candidates);
//          INVALID_ARGUMENT when the SEG's Frame of Reference differs from the series' (its
//          positions would mean other places), and read_seg's errors (FRACTIONAL segmentation,
//          no frames, truncated Pixel Data, frames that do not fit the series' grid), each naming
//          the file; a SEG refused so yields no structure set at all.
// Cost     O(frames x rows x columns + lines of the grid) plus marching cubes per segment.

#include <vector>

#include "core/base/status.h"
#include "dicom/import_dicom.h"

namespace soiq::dicom {

Result<ImportedStructureSet> import_seg(const DicomInstance& inst, const DicomScan& scan,
                                        const std::vector<SeriesImage>& images, const FindKnownSeries& known = {});

}  // namespace soiq::dicom
