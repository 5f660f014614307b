#include "dicom/seg_bit_packing.h"

#include <limits>
#include <string>

namespace soiq::dicom {

int64_t binary_pixel_data_bytes(int64_t rows, int64_t columns, int64_t frames) {
  return (rows * columns * frames + 7) / 8;
}

void BinaryFramePacker::add_frame(std::span<const uint8_t> pixels) {
  // The frame starts wherever the previous one ended, possibly mid-byte: that is the point.
  bytes_.resize(static_cast<size_t>((bit_count_ + static_cast<int64_t>(pixels.size()) + 7) / 8), 0);
  for (const uint8_t p : pixels) {
    if (p != 0) bytes_[static_cast<size_t>(bit_count_ >> 3)] |= static_cast<uint8_t>(1u << (bit_count_ & 7));
    ++bit_count_;
  }
}

std::vector<uint8_t> BinaryFramePacker::bytes() const {
  std::vector<uint8_t> out = bytes_;
  if (out.size() % 2 != 0) out.push_back(0);
  return out;
}

Result<std::vector<uint8_t>> unpack_binary_frame(std::span<const uint8_t> pixel_data, int64_t rows, int64_t columns,
                                                 int64_t frame_count, int64_t frame) {
  // Rows and Columns are US values; with them bounded, the bit count below cannot overflow.
  if (rows <= 0 || columns <= 0 || frame_count <= 0 || rows > 65535 || columns > 65535 ||
      frame_count > (std::numeric_limits<int64_t>::max() - 7) / (rows * columns))
    return invalid_argument("binary pixel data of " + std::to_string(rows) + " rows x " + std::to_string(columns) +
                            " columns x " + std::to_string(frame_count) +
                            " frames: rows and columns must be 1 to 65535, and frames at least 1");
  if (frame < 0 || frame >= frame_count)
    return invalid_argument("frame " + std::to_string(frame) + " asked of binary pixel data with " +
                            std::to_string(frame_count) + " frames (from 0)");
  // Checked before any read: a file must not make us read past its pixel data.
  const int64_t needed = binary_pixel_data_bytes(rows, columns, frame_count);
  if (static_cast<int64_t>(pixel_data.size()) < needed)
    return invalid_argument("binary pixel data of " + std::to_string(pixel_data.size()) + " bytes; " +
                            std::to_string(frame_count) + " frames of " + std::to_string(rows) + " x " +
                            std::to_string(columns) + " need " + std::to_string(needed));
  const int64_t pixels = rows * columns;
  std::vector<uint8_t> out(static_cast<size_t>(pixels));
  int64_t bit = frame * pixels;
  for (int64_t n = 0; n < pixels; ++n, ++bit)
    out[static_cast<size_t>(n)] = (pixel_data[static_cast<size_t>(bit >> 3)] >> (bit & 7)) & 1u;
  return out;
}

}  // namespace soiq::dicom
