// The separable distance transform against brute force (every pair of centres), exactly.
#include "core/regions/distance_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace soiq {
namespace {

// Squared distance in mm² from every voxel to the nearest source, by trying every source.
std::vector<double> brute_force(const std::vector<uint8_t>& src, const std::array<int64_t, 3>& d, const Vec3& s) {
  std::vector<double> out(src.size(), std::numeric_limits<double>::infinity());
  for (int64_t k = 0; k < d[2]; ++k)
    for (int64_t j = 0; j < d[1]; ++j)
      for (int64_t i = 0; i < d[0]; ++i)
        for (int64_t c = 0; c < d[2]; ++c)
          for (int64_t b = 0; b < d[1]; ++b)
            for (int64_t a = 0; a < d[0]; ++a) {
              if (!src[size_t(a + d[0] * (b + d[1] * c))]) continue;
              const double x = double(i - a) * s[0], y = double(j - b) * s[1], z = double(k - c) * s[2];
              double& o = out[size_t(i + d[0] * (j + d[1] * k))];
              o = std::min(o, x * x + y * y + z * z);
            }
  return out;
}

TEST(DistanceTransform, EqualsBruteForceOnRandomSourcesWithAnisotropicSpacing) {
  const std::array<int64_t, 3> d{13, 9, 7};
  const Vec3 spacing{0.7, 1.0, 2.5};
  std::mt19937_64 rng(11);
  for (double density : {0.01, 0.1, 0.5}) {
    std::bernoulli_distribution pick(density);
    std::vector<uint8_t> src(size_t(d[0] * d[1] * d[2]));
    for (auto& v : src) v = pick(rng) ? 1 : 0;
    const auto edt = squared_distance_transform(src, d, spacing, 2);
    ASSERT_TRUE(edt.ok()) << edt.status().to_string();
    const auto ref = brute_force(src, d, spacing);
    // Both are sums of three rounded squares; the envelope adds at most a few roundings.
    for (size_t i = 0; i < ref.size(); ++i) EXPECT_NEAR((*edt)[i], ref[i], 1e-9 * (1 + ref[i])) << i;
  }
}

TEST(DistanceTransform, SingleSourceGivesSquaredEuclideanDistanceInMm) {
  const std::array<int64_t, 3> d{5, 4, 3};
  std::vector<uint8_t> src(60, 0);
  src[0] = 1;  // voxel (0,0,0)
  const auto edt = squared_distance_transform(src, d, {0.5, 2.0, 3.0});
  ASSERT_TRUE(edt.ok());
  // Voxel (4,3,2): (4*0.5)^2 + (3*2)^2 + (2*3)^2 = 4 + 36 + 36.
  EXPECT_DOUBLE_EQ((*edt)[size_t(4 + 5 * (3 + 4 * 2))], 76.0);
}

TEST(DistanceTransform, NoSourceGivesInfinityEverywhere) {
  const auto edt = squared_distance_transform(std::vector<uint8_t>(24, 0), {2, 3, 4}, {1, 1, 1});
  ASSERT_TRUE(edt.ok());
  for (double v : *edt) EXPECT_EQ(v, std::numeric_limits<double>::infinity());
}

TEST(DistanceTransform, WrongFlagCountIsInvalidArgument) {
  const auto edt = squared_distance_transform(std::vector<uint8_t>(5, 0), {2, 3, 4}, {1, 1, 1});
  ASSERT_FALSE(edt.ok());
  EXPECT_EQ(edt.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(edt.status().message().find("source flags"), std::string::npos) << edt.status().message();
}

TEST(DistanceTransform, NonPositiveSpacingIsInvalidArgument) {
  const auto edt = squared_distance_transform(std::vector<uint8_t>(24, 0), {2, 3, 4}, {1, 0, 1});
  ASSERT_FALSE(edt.ok());
  EXPECT_EQ(edt.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(edt.status().message().find("spacing"), std::string::npos) << edt.status().message();
}

}  // namespace
}  // namespace soiq
