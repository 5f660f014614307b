#pragma once
// Binary SEG Pixel Data (Bits Allocated 1) packed and unpacked by soiq itself, as DICOM PS3.5 8.1.1
// and 8.2 lay it out: the bits of ALL frames follow each other with no padding between frames, the
// least significant bit of each byte first. Frame f's pixel n (row-major) is bit f x rows x
// columns + n of the whole stream; only the stream as a whole is padded, to an even byte count.
// DCMTK 3.6.7's SEG module pads every frame to a byte boundary instead, so its files are wrong, and
// standard files are misread, whenever rows x columns is not a multiple of 8: soiq does not use
// DCMTK for this layout (dicom/seg_export_frames.cpp, dicom/read_seg_frames.cpp). No DCMTK type
// appears here.
//
// BinaryFramePacker
//   Input    add_frame(pixels): one frame, one byte per pixel (row-major), nonzero = in the segment;
//            every frame of one stream has the same size.
//   Output   bytes(): the packed stream so far, ceil(bits / 8) bytes, unused bits of the last byte
//            0, and one 0 byte more when that count is odd (Pixel Data has an even length).
//   Cost     O(pixels) per frame; memory 1 bit per pixel.
// unpack_binary_frame
//   Input    pixel_data: the whole Pixel Data value; rows, columns, frame_count from the dataset;
//            frame from 0.
//   Output   frame `frame`, one byte (0 or 1) per pixel, row-major.
//   Errors   INVALID_ARGUMENT when rows, columns or frame_count is not positive, frame is not below
//            frame_count, or pixel_data holds fewer than binary_pixel_data_bytes(...) bytes.
//   Cost     O(rows x columns).
// Thread-safe: no shared state.

#include <cstdint>
#include <span>
#include <vector>

#include "core/base/status.h"

namespace soiq::dicom {

// ceil(rows x columns x frames / 8): the bytes a binary Pixel Data needs, before the even padding.
// The product must fit in 64 bits (unpack_binary_frame checks that before calling it).
int64_t binary_pixel_data_bytes(int64_t rows, int64_t columns, int64_t frames);

class BinaryFramePacker {
 public:
  void add_frame(std::span<const uint8_t> pixels);
  std::vector<uint8_t> bytes() const;
  int64_t bit_count() const { return bit_count_; }

 private:
  std::vector<uint8_t> bytes_;
  int64_t bit_count_ = 0;
};

Result<std::vector<uint8_t>> unpack_binary_frame(std::span<const uint8_t> pixel_data, int64_t rows, int64_t columns,
                                                 int64_t frame_count, int64_t frame);

}  // namespace soiq::dicom
