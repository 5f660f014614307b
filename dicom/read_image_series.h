#pragma once
// An image series as a soiq::Image (issue 5 deliverable 1): geometry from the slices' positions
// and orientation (dicom/slice_stack.h), voxel values as modality values.
//
// Inputs   series: a series from scan_dicom (its instances' files are read in full).
//          max_voxels: RESOURCE_EXHAUSTED above this many voxels, checked before pixels are read.
// Output   SeriesImage: image.geometry as slice_stack gives it; image.voxels[i + nx*(j + ny*k)] =
//          RescaleSlope_k * stored + RescaleIntercept_k of slice k (slope 1, intercept 0 when
//          absent), times the SUV factor for PT (dicom/pet_suv.h). `units`: "HU" for CT, "SUVbw"
//          for PET converted or stored as SUV, the stored Units otherwise (`units_note` then says
//          why there is no SUV), "" for other modalities. slice_sop_instance_uids[k] and
//          slice_paths[k] name slice k.
// Errors   INVALID_ARGUMENT (message names the slice or file): a series with no instances, a
//          multi-frame or colour instance, a slice without Image Position / Orientation / Pixel
//          Spacing, and every geometry error of slice_stack (missing slice, irregular spacing,
//          mixed orientation or size). UNIMPLEMENTED for encapsulated (compressed) pixel data,
//          naming the transfer syntax. DATA_LOSS for unreadable files or pixel data shorter than
//          Rows x Columns. RESOURCE_EXHAUSTED over max_voxels.
// Cost     O(files + voxels); reads each file once. Thread-safe (no shared state).

#include <string>
#include <vector>

#include "core/image.h"
#include "core/status.h"
#include "dicom/records.h"

namespace soiq::dicom {

struct SeriesImage {
  std::string series_uid;
  std::string modality;
  Image image;
  std::string units;
  std::string units_note;
  std::vector<std::string> slice_sop_instance_uids;  // by k
  std::vector<std::string> slice_paths;              // by k
};

Result<SeriesImage> read_image_series(const DicomSeries& series, int64_t max_voxels = kDefaultMaxVoxels);

}  // namespace soiq::dicom
