#pragma once
// An image series as a soiq::Image: geometry from the slices' positions
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
// Errors   INVALID_ARGUMENT naming the file (or slice) and the tag, before any value of a slice is
//          trusted: a series with no instances; Number of Frames other than 1 (multi-frame);
//          Samples per Pixel other than 1 (colour); Rows or Columns missing or 0, or different from
//          the first slice's; Bits Allocated other than 8, 16, 32, or Bits Stored / High Bit that do
//          not fit it; Pixel Data whose length is not Rows x Columns x Bits Allocated / 8 (plus one
//          pad byte to an even length); Rescale Slope or Intercept present but not a finite
//          number, a slope below float's smallest normal (every voxel the same), or a slope and
//          intercept that take a value Bits Stored allows beyond float's range; for a single
//          slice, a Spacing Between Slices / Slice Thickness that is not finite; a PET SUV factor
//          that takes a voxel beyond float; a slice without Image Position / Orientation / Pixel
//          Spacing; and every geometry error of slice_stack (non-finite or out-of-range position,
//          orientation or spacing, missing slice, irregular spacing, mixed orientation or size).
//          UNIMPLEMENTED for encapsulated (compressed) pixel data without a decoder, naming the
//          transfer syntax. DATA_LOSS for unreadable files or Pixel Data DCMTK cannot read.
//          RESOURCE_EXHAUSTED over max_voxels (checked on the first slice's Rows x Columns x the
//          number of slices, before any pixels are decoded).
// Cost     O(files + voxels); reads each file once. Thread-safe (no shared state).

#include <string>
#include <vector>

#include "core/base/image.h"
#include "core/base/status.h"
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
