// Binary SEG Pixel Data packing (dicom/seg_bit_packing.h): frames back to back, least significant
// bit first, as PS3.5 8.1.1 / 8.2 lay them out. The oracle is a hand-built byte stream and a plain
// bit-by-bit reading of the standard's rule, independent of the code under test.
#include "dicom/seg_bit_packing.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace soiq::dicom {
namespace {

// Pseudo-random frame contents, about half the pixels set.
std::vector<uint8_t> pattern(size_t n, uint32_t seed) {
  std::vector<uint8_t> out(n);
  uint32_t x = seed;
  for (uint8_t& p : out) p = ((x = x * 1664525u + 1013904223u) >> 28) & 1u;
  return out;
}

// Frame f's pixel n is bit f x rows x columns + n of the stream: byte bit / 8, bit bit % 8 (LSB first).
uint8_t standard_bit(const std::vector<uint8_t>& stream, int64_t bit) { return (stream[bit / 8] >> (bit % 8)) & 1u; }

TEST(SegBitPacking, HandBuiltStreamOfThreeFramesOfFivePixels) {
  // Rows 1 x Columns 5: frame 1 starts at bit 5 of byte 0, frame 2 at bit 2 of byte 1.
  // frame 0 = 1 0 1 1 0, frame 1 = 0 1 1 0 1, frame 2 = 1 1 0 0 1
  // byte 0 bits 0..7 = 1 0 1 1 0 | 0 1 1      -> 0b11001101 = 0xCD
  // byte 1 bits 0..7 = 0 1 | 1 1 0 0 1 | 0(*) -> 0b01001110 = 0x4E (* unused, 0)
  const std::vector<std::vector<uint8_t>> frames = {{1, 0, 1, 1, 0}, {0, 1, 1, 0, 1}, {1, 1, 0, 0, 1}};
  BinaryFramePacker packer;
  for (const auto& f : frames) packer.add_frame(f);
  EXPECT_EQ(packer.bit_count(), 15);
  EXPECT_EQ(packer.bytes(), (std::vector<uint8_t>{0xCD, 0x4E}));
  for (int64_t f = 0; f < 3; ++f) {
    auto back = unpack_binary_frame(std::vector<uint8_t>{0xCD, 0x4E}, 1, 5, 3, f);
    ASSERT_TRUE(back.ok()) << back.status().to_string();
    EXPECT_EQ(*back, frames[static_cast<size_t>(f)]) << "frame " << f;
  }
}

TEST(SegBitPacking, NonzeroBytesAreSetPixels) {
  BinaryFramePacker packer;
  packer.add_frame(std::vector<uint8_t>{0, 255, 7, 0, 1, 0, 0, 0, 2});  // 9 pixels, one frame
  EXPECT_EQ(packer.bytes(), (std::vector<uint8_t>{0x16, 0x01}));
}

TEST(SegBitPacking, StreamIsPaddedToAnEvenLengthWithZeros) {
  BinaryFramePacker packer;
  packer.add_frame(std::vector<uint8_t>(3, 1));  // 3 bits -> 1 byte -> 2 with the padding
  EXPECT_EQ(packer.bytes(), (std::vector<uint8_t>{0x07, 0x00}));
  EXPECT_EQ(binary_pixel_data_bytes(1, 3, 1), 1);
}

struct Size {
  int64_t rows, columns;
};

class SegBitPackingRoundTrip : public ::testing::TestWithParam<Size> {};

// Every residue of rows x columns mod 8, each over 7 frames so that frames start at many bit offsets.
TEST_P(SegBitPackingRoundTrip, FramesFollowEachOtherWithoutPadding) {
  const auto [rows, columns] = GetParam();
  const int64_t pixels = rows * columns, frame_count = 7;
  std::vector<std::vector<uint8_t>> frames;
  BinaryFramePacker packer;
  for (int64_t f = 0; f < frame_count; ++f) {
    frames.push_back(pattern(static_cast<size_t>(pixels), static_cast<uint32_t>(f + 1)));
    packer.add_frame(frames.back());
  }
  const std::vector<uint8_t> stream = packer.bytes();
  const int64_t needed = (pixels * frame_count + 7) / 8;
  EXPECT_EQ(binary_pixel_data_bytes(rows, columns, frame_count), needed);
  EXPECT_EQ(static_cast<int64_t>(stream.size()), needed + needed % 2);
  for (int64_t f = 0; f < frame_count; ++f)
    for (int64_t n = 0; n < pixels; ++n)
      ASSERT_EQ(standard_bit(stream, f * pixels + n), frames[f][n]) << "frame " << f << " pixel " << n;
  for (int64_t bit = pixels * frame_count; bit < 8 * static_cast<int64_t>(stream.size()); ++bit)
    EXPECT_EQ(standard_bit(stream, bit), 0) << "padding bit " << bit;
  for (int64_t f = 0; f < frame_count; ++f) {
    auto back = unpack_binary_frame(stream, rows, columns, frame_count, f);
    ASSERT_TRUE(back.ok()) << back.status().to_string();
    EXPECT_EQ(*back, frames[static_cast<size_t>(f)]) << "frame " << f;
  }
}

// rows x columns mod 8 = 0, 1, ..., 7 in this order.
INSTANTIATE_TEST_SUITE_P(AllResidues, SegBitPackingRoundTrip,
                         ::testing::Values(Size{4, 6}, Size{7, 7}, Size{9, 10}, Size{9, 11}, Size{12, 13}, Size{9, 13},
                                           Size{10, 11}, Size{9, 15}, Size{1, 1}),
                         [](const auto& info) {
                           return std::to_string(info.param.rows) + "x" + std::to_string(info.param.columns);
                         });

TEST(SegBitPacking, ShortStreamIsInvalidArgumentBeforeAnyRead) {
  // 3 frames of 3 x 3 need ceil(27 / 8) = 4 bytes.
  auto r = unpack_binary_frame(std::vector<uint8_t>{0xFF, 0xFF, 0xFF}, 3, 3, 3, 0);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("3 bytes"), std::string::npos) << r.status().to_string();
  EXPECT_NE(r.status().message().find("need 4"), std::string::npos) << r.status().to_string();
}

TEST(SegBitPacking, FrameOutOfRangeIsInvalidArgument) {
  const std::vector<uint8_t> stream(4, 0);
  for (int64_t f : {-1, 3}) {
    auto r = unpack_binary_frame(stream, 3, 3, 3, f);
    ASSERT_FALSE(r.ok()) << f;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  }
}

TEST(SegBitPacking, ZeroOrHugeSizesAreInvalidArgumentWithoutOverflow) {
  const std::vector<uint8_t> stream(4, 0);
  const Size sizes[] = {{0, 3}, {3, 0}, {-1, 3}, {70000, 3}};
  for (const Size& s : sizes) {
    auto r = unpack_binary_frame(stream, s.rows, s.columns, 1, 0);
    ASSERT_FALSE(r.ok()) << s.rows << " x " << s.columns;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  }
  for (int64_t frames : {int64_t{0}, int64_t{1} << 62}) {
    auto r = unpack_binary_frame(stream, 65535, 65535, frames, 0);
    ASSERT_FALSE(r.ok()) << frames;
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  }
}

}  // namespace
}  // namespace soiq::dicom
