// Volume shape features against hand counts (boxes of voxels have exact moments) and a brute-force
// evaluation over the dense mask with an oblique grid.
#include "core/features/volume_shape.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/geometry/symmetric_eigenvalues.h"

namespace soiq {
namespace {

ImageGeometry grid(std::array<int64_t, 3> dims, Vec3 spacing, Vec3 origin = {0, 0, 0}, Mat3 d = identity3()) {
  ImageGeometry g;
  g.dims = dims;
  g.spacing_mm = spacing;
  g.origin_mm = origin;
  g.direction = d;
  return g;
}

// A rotation (orthonormal, det +1) from a unit quaternion.
Mat3 rotation(double w, double x, double y, double z) {
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  w /= n, x /= n, y /= n, z /= n;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
           {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
           {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

Mask box_mask(const ImageGeometry& g, std::array<int64_t, 3> lo, std::array<int64_t, 3> hi) {
  Mask m{g, std::vector<uint8_t>(size_t(g.voxel_count()), 0)};
  for (int64_t k = lo[2]; k < hi[2]; ++k) {
    for (int64_t j = lo[1]; j < hi[1]; ++j) {
      for (int64_t i = lo[0]; i < hi[0]; ++i) m.voxels[size_t(i + g.dims[0] * (j + g.dims[1] * k))] = 1;
    }
  }
  return m;
}

VolumeShape must(const RunLengthVolume& v) {
  auto r = volume_shape(v);
  EXPECT_TRUE(r.ok()) << r.status().to_string();
  return r.ok() ? *r : VolumeShape{};
}

TEST(VolumeShape, OneVoxelHasZeroAxesAndUndefinedRatios) {
  const auto g = grid({3, 3, 3}, {0.5, 2, 3}, {10, 20, 30});
  const auto s = must(from_mask(box_mask(g, {1, 1, 1}, {2, 2, 2})));
  EXPECT_EQ(s.voxel_count, 1);
  EXPECT_DOUBLE_EQ(s.voxel_volume_mm3, 3);
  EXPECT_EQ(s.centroid_mm, (Vec3{10.5, 22, 33}));
  EXPECT_EQ(s.bbox_min_mm, s.centroid_mm);
  EXPECT_EQ(s.bbox_max_mm, s.centroid_mm);
  EXPECT_EQ(s.major_axis_length_mm, 0);
  EXPECT_TRUE(std::isnan(s.elongation));
  EXPECT_TRUE(std::isnan(s.flatness));
}

TEST(VolumeShape, BoxOfVoxelsHasExactDiscreteVariances) {
  // n voxel centres spaced s apart have variance s^2 (n^2 - 1) / 12 (hand count).
  const auto g = grid({12, 9, 7}, {0.7, 1.3, 2.5}, {-5, 3, 11});
  const auto s = must(from_mask(box_mask(g, {0, 2, 3}, {12, 6, 6})));  // 12 x 4 x 3 voxels
  EXPECT_EQ(s.voxel_count, 144);
  EXPECT_NEAR(s.voxel_volume_mm3, 144 * 0.7 * 1.3 * 2.5, 1e-12);
  const double vx = 0.49 * 143 / 12, vy = 1.69 * 15 / 12, vz = 6.25 * 8 / 12;  // 5.84 > 4.17 > 2.11
  EXPECT_NEAR(s.major_axis_length_mm, 4 * std::sqrt(vx), 1e-12);
  EXPECT_NEAR(s.minor_axis_length_mm, 4 * std::sqrt(vz), 1e-12);
  EXPECT_NEAR(s.least_axis_length_mm, 4 * std::sqrt(vy), 1e-12);
  EXPECT_NEAR(s.elongation, std::sqrt(vz / vx), 1e-14);
  EXPECT_NEAR(s.flatness, std::sqrt(vy / vx), 1e-14);
  const Vec3 centre = g.index_to_physical({5.5, 3.5, 4});
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(s.centroid_mm[a], centre[a], 1e-12);
  EXPECT_EQ(s.bbox_min_mm, g.index_to_physical({0, 2, 3}));
  EXPECT_EQ(s.bbox_max_mm, g.index_to_physical({11, 5, 5}));
}

// Runs far from the origin and longer than 2^20 voxels (the 64-bit shortcut's limit): the
// index moments stay exact, so two runs on one line have the hand-counted variance.
TEST(VolumeShape, LongRunsFarFromTheOriginHaveExactMoments) {
  const int64_t nx = (int64_t(1) << 22) + 7;
  const auto g = grid({nx, 1, 1}, {1, 1, 1});
  for (const auto& [b, n] : {std::pair<int32_t, int32_t>{3'000'000, 1'000'003},
                             std::pair<int32_t, int32_t>{5, 3'000'001}, std::pair<int32_t, int32_t>{1, 1}}) {
    RunLengthVolume v = empty_volume(g);
    v.runs = {{b, b + n}};
    v.line_start = {0, 1};
    const auto s = must(v);
    EXPECT_EQ(s.voxel_count, n);
    EXPECT_EQ(s.centroid_mm[0], b + (double(n) - 1) / 2) << n;
    // n centres 1 mm apart: variance (n^2 - 1) / 12, the major axis 4 sqrt of it.
    const double variance = (double(n) * double(n) - 1) / 12;
    EXPECT_NEAR(s.major_axis_length_mm, 4 * std::sqrt(variance), 1e-12 * (1 + 4 * std::sqrt(variance))) << n;
  }
}

TEST(VolumeShape, SampleCovarianceScalesByNOverNMinus1) {
  const auto g = grid({12, 9, 7}, {0.7, 1.3, 2.5});
  const auto v = from_mask(box_mask(g, {0, 2, 3}, {12, 6, 6}));  // 144 voxels
  const auto population = must(v);
  const auto sample = volume_shape(v, CovarianceDivisor::kNMinus1);
  ASSERT_TRUE(sample.ok());
  const double f = std::sqrt(144.0 / 143.0);
  EXPECT_NEAR(sample->major_axis_length_mm, f * population.major_axis_length_mm, 1e-12);
  EXPECT_NEAR(sample->least_axis_length_mm, f * population.least_axis_length_mm, 1e-12);
  EXPECT_NEAR(sample->elongation, population.elongation, 1e-14);
  EXPECT_EQ(sample->centroid_mm, population.centroid_mm);
}

TEST(VolumeShape, SampleCovarianceOfOneVoxelIsZero) {
  const auto g = grid({2, 2, 2}, {1, 1, 1});
  const auto s = volume_shape(from_mask(box_mask(g, {1, 1, 1}, {2, 2, 2})), CovarianceDivisor::kNMinus1);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->major_axis_length_mm, 0);
}

TEST(VolumeShape, FlatStructureHasZeroLeastAxis) {
  const auto g = grid({6, 6, 3}, {1, 1, 1});
  const auto s = must(from_mask(box_mask(g, {0, 0, 1}, {6, 3, 2})));
  EXPECT_EQ(s.least_axis_length_mm, 0);
  EXPECT_EQ(s.flatness, 0);
}

TEST(VolumeShape, MatchesBruteForceOnObliqueGrid) {
  // A random blob on a rotated, anisotropic grid: every output against direct sums over the dense
  // mask in LPS (two-pass covariance), which share no code with the per-run closed forms.
  const auto g = grid({23, 17, 11}, {0.9, 1.1, 2.7}, {-40, 12.5, 300}, rotation(0.9, 0.2, -0.3, 0.4));
  std::mt19937_64 rng(3);
  std::bernoulli_distribution coin(0.45);
  Mask m{g, std::vector<uint8_t>(size_t(g.voxel_count()))};
  for (auto& v : m.voxels) v = coin(rng) ? 1 : 0;
  const auto s = must(from_mask(m));

  std::vector<Vec3> p;
  for (int64_t k = 0; k < g.dims[2]; ++k) {
    for (int64_t j = 0; j < g.dims[1]; ++j) {
      for (int64_t i = 0; i < g.dims[0]; ++i) {
        if (m.voxels[size_t(i + g.dims[0] * (j + g.dims[1] * k))])
          p.push_back(g.index_to_physical({double(i), double(j), double(k)}));
      }
    }
  }
  ASSERT_EQ(s.voxel_count, int64_t(p.size()));
  Vec3 mean{0, 0, 0}, lo = p[0], hi = p[0];
  for (const auto& q : p) {
    mean = mean + q;
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], q[a]), hi[a] = std::max(hi[a], q[a]);
  }
  mean = (1.0 / double(p.size())) * mean;
  Mat3 cov{};
  for (const auto& q : p) {
    const Vec3 d = q - mean;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) cov[r][c] += d[r] * d[c] / double(p.size());
    }
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(s.centroid_mm[a], mean[a], 1e-10);
    EXPECT_NEAR(s.bbox_min_mm[a], lo[a], 1e-10);
    EXPECT_NEAR(s.bbox_max_mm[a], hi[a], 1e-10);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.covariance_mm2[a][c], cov[a][c], 1e-10);
  }
  const Vec3 l = symmetric_eigenvalues(cov);
  EXPECT_NEAR(s.major_axis_length_mm, 4 * std::sqrt(l[0]), 1e-10);
  EXPECT_NEAR(s.minor_axis_length_mm, 4 * std::sqrt(l[1]), 1e-10);
  EXPECT_NEAR(s.least_axis_length_mm, 4 * std::sqrt(l[2]), 1e-10);
}

TEST(VolumeShape, EmptyVolumeIsInvalidArgument) {
  const auto r = volume_shape(empty_volume(grid({4, 4, 4}, {1, 1, 1})));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("no inside voxel"), std::string::npos);
}

TEST(VolumeShape, MalformedRunTableIsInvalidArgument) {
  auto v = empty_volume(grid({4, 4, 4}, {1, 1, 1}));
  v.line_start.pop_back();
  const auto r = volume_shape(v);
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("line starts"), std::string::npos);
}

TEST(VolumeShape, InvalidGeometryIsInvalidArgument) {
  auto v = empty_volume(grid({4, 4, 4}, {1, 1, 1}));
  v.geometry.spacing_mm[1] = 0;
  EXPECT_EQ(volume_shape(v).status().code(), StatusCode::kInvalidArgument);
}

}  // namespace
}  // namespace soiq
