// The delta-planes stream codec on its own: exact round trips at any stride, through both of its
// block kinds (LZ4 and stored), and DATA_LOSS for what a corrupt stream can look like.
#include "db/delta_planes.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "core/base/cpu_level.h"

namespace soiq::db {
namespace {

template <typename U>
void expect_round_trip(const std::vector<U>& values, size_t stride_values) {
  // The values sit `stride_values` apart in a wider array, as a coordinate does in a Vec3 array.
  std::vector<U> spread(values.size() * stride_values + 1, U(0xAB));
  for (size_t i = 0; i < values.size(); ++i) spread[i * stride_values] = values[i];
  std::string stream;
  append_delta_planes(spread.data(), values.size(), int(sizeof(U)), stride_values * sizeof(U), stream);
  std::vector<U> back(spread.size(), U(0xCD));
  size_t at = 0;
  const Status s = read_delta_planes(stream, at, values.size(), int(sizeof(U)), stride_values * sizeof(U), back.data());
  ASSERT_TRUE(s.ok()) << s.to_string();
  EXPECT_EQ(at, stream.size());
  for (size_t i = 0; i < back.size(); ++i) {
    const bool ours = i % stride_values == 0 && i / stride_values < values.size();
    if (ours) {
      ASSERT_EQ(back[i], values[i / stride_values]) << i;
    } else {
      ASSERT_EQ(back[i], U(0xCD)) << "wrote outside its values at " << i;  // the gaps are untouched
    }
  }
}

TEST(DeltaPlanes, RandomAndSmoothValuesRoundTripAtAnyStride) {
  std::mt19937_64 rng(5);
  for (size_t n : {size_t{0}, size_t{1}, size_t{16}, size_t{17}, size_t{65536}, size_t{65537}, size_t{200000}}) {
    std::vector<uint64_t> random(n), smooth(n);
    std::vector<uint32_t> corners(n);
    uint64_t walk = 0x4059000000000000ull;
    int64_t corner = 1000;
    for (size_t i = 0; i < n; ++i) {
      random[i] = rng();  // incompressible: stored blocks
      walk += rng() % 4096 - 2048;
      smooth[i] = walk;  // LZ4 blocks
      corner += int64_t(rng() % 7) - 3;
      corners[i] = uint32_t(corner);
    }
    expect_round_trip(random, 1);
    expect_round_trip(random, 3);
    expect_round_trip(smooth, 3);
    expect_round_trip(corners, 3);
    expect_round_trip(corners, 1);
  }
}

// The decoder is compiled per CPU level (core/base/cpu_dispatch.h): each level this CPU runs
// decodes every value exactly.
TEST(DeltaPlanes, EveryCpuLevelDecodesExactly) {
  std::mt19937_64 rng(11);
  std::vector<uint64_t> smooth(70001);
  std::vector<uint32_t> corners(70001);
  uint64_t walk = 0x4059000000000000ull;
  for (size_t i = 0; i < smooth.size(); ++i) {
    walk += rng() % 4096 - 2048;
    smooth[i] = walk;
    corners[i] = uint32_t(rng() % 100000);
  }
  for (const CpuLevel level : {CpuLevel::kBaseline, CpuLevel::kV2, CpuLevel::kV3}) {
    if (int(level) > int(detected_cpu_level())) continue;
    SCOPED_TRACE(std::string(cpu_level_name(level)));
    cap_cpu_level(level);
    expect_round_trip(smooth, 3);
    expect_round_trip(corners, 3);
  }
  cap_cpu_level(std::nullopt);
}

TEST(DeltaPlanes, SmoothValuesTakeLessThanTheirBytes) {
  std::vector<uint64_t> smooth(100000);
  for (size_t i = 0; i < smooth.size(); ++i) smooth[i] = 0x4059000000000000ull + i * 977;
  std::string stream;
  append_delta_planes(smooth.data(), smooth.size(), 8, 8, stream);
  EXPECT_LT(stream.size(), smooth.size() * 8 / 10);
}

TEST(DeltaPlanes, CorruptStreamsAreDataLoss) {
  std::vector<uint32_t> v(5000);
  for (size_t i = 0; i < v.size(); ++i) v[i] = uint32_t(i / 3);
  std::string stream;
  append_delta_planes(v.data(), v.size(), 4, 4, stream);
  std::vector<uint32_t> back(v.size());
  auto read = [&](const std::string& s) {
    size_t at = 0;
    return read_delta_planes(s, at, v.size(), 4, 4, back.data());
  };
  EXPECT_EQ(read(stream.substr(0, 3)).code(), StatusCode::kDataLoss);                  // no block header
  EXPECT_EQ(read(stream.substr(0, stream.size() - 1)).code(), StatusCode::kDataLoss);  // block cut short
  std::string wrong_size = stream;
  const uint32_t huge = 0x7fffffff;
  std::memcpy(wrong_size.data(), &huge, 4);
  EXPECT_EQ(read(wrong_size).code(), StatusCode::kDataLoss);
  std::string stored_of_wrong_size = stream;
  const uint32_t stored = (1u << 31) | uint32_t(stream.size() - 4);
  std::memcpy(stored_of_wrong_size.data(), &stored, 4);
  EXPECT_EQ(read(stored_of_wrong_size).code(), StatusCode::kDataLoss);
}

}  // namespace
}  // namespace soiq::db
