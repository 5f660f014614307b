#pragma once
// Internal to dicom/read_seg*.cpp, not part of read_seg_file's interface (read_seg.h): the frames of
// a binary SEG, read by soiq rather than DCMTK. read_seg.cpp reads the header, identity and
// segment descriptions; read_seg_frames.cpp reads the Pixel Data (checked against what the header
// claims), places each frame on a slice of the grid and turns a segment's frames into runs.
// Includes DCMTK, which the public headers of dicom/ never do.

#include <dcmtk/config/osconfig.h>  // must come first for DCMTK
#include <dcmtk/dcmdata/dctk.h>
#include <dcmtk/dcmfg/fginterface.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "core/base/image_geometry.h"
#include "core/base/run_length_volume.h"
#include "core/base/status.h"

namespace soiq::dicom {

// A frame placed on the grid: DCMTK's frame index and the slice it lies on.
struct FrameOnGrid {
  size_t frame = 0;  // DCMTK's frame index, from 0
  int64_t k = 0;
};

// "SEG frame <f + 1>": frames are named from 1 in messages.
inline std::string frame_name(size_t f) { return "SEG frame " + std::to_string(f + 1); }

// The Pixel Data of a binary SEG, checked against what its header claims before anything is read.
struct BinaryPixels {
  int64_t rows = 0, columns = 0, frames = 0;
  std::vector<uint8_t> words_as_bytes;  // the bytes of an OW value, little-endian as in the file
  std::span<const uint8_t> bytes;       // the whole Pixel Data value
};

// The Segmentation Type, Bits Allocated, Rows, Columns and NumberOfFrames of `ds`, then its Pixel
// Data (decompressed) with at least the bytes they need. `path` only names the object in messages,
// as `seg` does ("SEG '<path>'").
Result<BinaryPixels> binary_pixels(DcmDataset& ds, const std::string& path, const std::string& seg);

// Slice k of `grid` that frame f lies on, or INVALID_ARGUMENT saying what does not fit.
Result<int64_t> slice_of_frame(FGInterface& fg, size_t f, const ImageGeometry& grid);

// The SOP instance uid of frame f's first Derivation Image Source Image, "" when there is none.
std::string frame_source_uid(FGInterface& fg, size_t f);

// Runs of one segment from its frames (sorted by k): slice by slice, frames on one slice united.
Result<RunLengthVolume> segment_volume(const BinaryPixels& pixels, const std::vector<FrameOnGrid>& frames,
                                       const ImageGeometry& grid);

}  // namespace soiq::dicom
