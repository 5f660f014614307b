// Intensity statistics against the IBSI-1 digital phantom (REFERENCE_VALUES.md) and hand counts.
#include "core/features/intensity_features.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "core/io/read_image.h"
#include "core/regions/resample.h"

namespace soiq {
namespace {

IntensityFeatures phantom_features() {
  const std::string dir = std::string(SOIQ_TEST_DATA_DIR) + "/ibsi_digital_phantom/";
  auto image = read_image(dir + "phantom.nii.gz");
  auto mask = read_image(dir + "mask.nii.gz");
  EXPECT_TRUE(image.ok() && mask.ok());
  if (!image.ok() || !mask.ok()) return {};
  const RunLengthVolume region = from_mask(mask_from_image(*mask));
  auto samples = resample(*image, region, Interpolation::kNearest);
  EXPECT_TRUE(samples.ok()) << samples.status().to_string();
  if (!samples.ok()) return {};
  EXPECT_TRUE(samples->same_grid);
  auto f = intensity_features(samples->values);
  EXPECT_TRUE(f.ok()) << f.status().to_string();
  return f.ok() ? *f : IntensityFeatures{};
}

// IBSI publishes 3 significant digits: a value matches when it rounds to the published one, i.e.
// lies within half a unit of its last digit (`half_unit`).
TEST(IntensityFeatures, IbsiDigitalPhantomMatchesConsensusValues) {
  const IntensityFeatures f = phantom_features();
  EXPECT_EQ(f.voxel_count, 74);  // 592 mm³ / 8 mm³
  EXPECT_NEAR(f.mean, 2.15, 0.005);
  EXPECT_NEAR(f.variance, 3.05, 0.005);
  EXPECT_NEAR(f.standard_deviation, std::sqrt(f.variance), 1e-12);
  EXPECT_NEAR(f.skewness, 1.08, 0.005);
  EXPECT_NEAR(f.excess_kurtosis, -0.355, 0.0005);
  EXPECT_NEAR(f.mean_absolute_deviation, 1.55, 0.005);
  EXPECT_NEAR(f.energy, 567, 0.5);
  EXPECT_NEAR(f.root_mean_square, 2.77, 0.005);
  // Order statistics of integer data are exact.
  EXPECT_EQ(f.median, 1);
  EXPECT_EQ(f.minimum, 1);
  EXPECT_EQ(f.p10, 1);
  EXPECT_EQ(f.p90, 4);
  EXPECT_EQ(f.maximum, 6);
  EXPECT_EQ(f.interquartile_range, 3);
  EXPECT_EQ(f.range, 5);
}

TEST(IntensityFeatures, HandCountOfFourValues) {
  auto f = intensity_features({4, 1, 3, 2});
  ASSERT_TRUE(f.ok());
  EXPECT_DOUBLE_EQ(f->mean, 2.5);
  EXPECT_DOUBLE_EQ(f->variance, 1.25);                // (2.25 + 0.25 + 0.25 + 2.25) / 4
  EXPECT_DOUBLE_EQ(f->skewness, 0.0);                 // symmetric
  EXPECT_DOUBLE_EQ(f->excess_kurtosis, 1.64 - 3.0);   // m4 = (5.0625*2 + 0.0625*2)/4 = 2.5625; /1.5625
  EXPECT_DOUBLE_EQ(f->median, 2.5);                   // rank 1.5
  EXPECT_DOUBLE_EQ(f->p10, 1.3);                      // rank 0.3
  EXPECT_DOUBLE_EQ(f->p90, 3.7);                      // rank 2.7
  EXPECT_DOUBLE_EQ(f->interquartile_range, 1.5);      // 3.25 - 1.75
  EXPECT_DOUBLE_EQ(f->mean_absolute_deviation, 1.0);  // (1.5 + 0.5 + 0.5 + 1.5) / 4
  EXPECT_DOUBLE_EQ(f->energy, 30.0);
  EXPECT_DOUBLE_EQ(f->root_mean_square, std::sqrt(7.5));
}

TEST(IntensityFeatures, ConstantRegionHasZeroSkewnessAndKurtosis) {
  auto f = intensity_features({7, 7, 7});
  ASSERT_TRUE(f.ok());
  EXPECT_EQ(f->variance, 0);
  EXPECT_EQ(f->skewness, 0);
  EXPECT_EQ(f->excess_kurtosis, 0);
  EXPECT_EQ(f->range, 0);
}

TEST(IntensityFeatures, NoValuesIsInvalidArgument) {
  auto f = intensity_features({});
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(f.status().message().find("no intensity values"), std::string::npos) << f.status().message();
}

TEST(IntensityFeatures, NanValueIsInvalidArgument) {
  auto f = intensity_features({1, std::numeric_limits<double>::quiet_NaN()});
  ASSERT_FALSE(f.ok());
  EXPECT_EQ(f.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(f.status().message().find("NaN"), std::string::npos) << f.status().message();
}

// The percentiles come from selection, not a sort: on random lists of every small size (with many
// ties) and a few large ones, each order statistic equals the one of a fully sorted copy exactly.
TEST(IntensityFeatures, PercentilesBySelectionEqualThoseOfASortedCopy) {
  std::mt19937_64 rng(7);
  auto sorted_percentile = [](const std::vector<double>& s, double p) {
    const double h = double(s.size() - 1) * p;
    const size_t lo = size_t(std::floor(h)), hi = std::min(lo + 1, s.size() - 1);
    return s[lo] + (h - double(lo)) * (s[hi] - s[lo]);
  };
  for (size_t n : {1, 2, 3, 4, 5, 6, 7, 9, 10, 11, 13, 20, 21, 99, 100, 101, 1000, 100003}) {
    for (int trial = 0; trial < 5; ++trial) {
      std::vector<double> values(n);
      std::uniform_int_distribution<int> small(-5, 5);
      std::normal_distribution<double> wide(100, 30);
      for (double& v : values) v = trial % 2 ? double(small(rng)) : wide(rng);
      std::vector<double> sorted = values;
      std::sort(sorted.begin(), sorted.end());
      auto f = intensity_features(values);
      ASSERT_TRUE(f.ok());
      EXPECT_EQ(f->minimum, sorted.front());
      EXPECT_EQ(f->maximum, sorted.back());
      EXPECT_EQ(f->median, sorted_percentile(sorted, 0.5)) << n;
      EXPECT_EQ(f->p10, sorted_percentile(sorted, 0.1)) << n;
      EXPECT_EQ(f->p90, sorted_percentile(sorted, 0.9)) << n;
      EXPECT_EQ(f->interquartile_range, sorted_percentile(sorted, 0.75) - sorted_percentile(sorted, 0.25)) << n;
    }
  }
}

// The bucketed selection stays exact at the edges of its value-to-bucket map: a range that
// overflows, a range of a few ulps, signed zeros, and ranks in the first and last bucket.
TEST(IntensityFeatures, PercentilesAreExactOnExtremeRanges) {
  std::mt19937_64 rng(3);
  const double big = std::numeric_limits<double>::max();
  const std::vector<std::vector<double>> bases = {{-big, big, 0, 1e300, -1e300},
                                                  {1.0, std::nextafter(1.0, 2.0), std::nextafter(1.0, 0.0)},
                                                  {-0.0, 0.0, 1e-300},
                                                  {0, 0, 0, 1e9},
                                                  {5e-324, 0, 1e-320}};
  for (const std::vector<double>& base : bases) {
    for (size_t n : {2, 17, 1000, 50001}) {
      std::vector<double> values(n);
      for (double& v : values) v = base[rng() % base.size()];
      std::vector<double> sorted = values;
      std::sort(sorted.begin(), sorted.end());
      auto f = intensity_features(values);
      if (!f.ok()) continue;  // moments overflow to infinity on +-DBL_MAX: not this test's subject
      const double h = double(n - 1) * 0.5;
      const size_t lo = size_t(std::floor(h)), hi = std::min(lo + 1, n - 1);
      EXPECT_EQ(f->median, sorted[lo] + (h - double(lo)) * (sorted[hi] - sorted[lo])) << n;
      const double h10 = double(n - 1) * 0.1;
      const size_t l10 = size_t(std::floor(h10)), u10 = std::min(l10 + 1, n - 1);
      EXPECT_EQ(f->p10, sorted[l10] + (h10 - double(l10)) * (sorted[u10] - sorted[l10])) << n;
    }
  }
}

// One far outlier puts every other value into the lowest bucket: all ten ranks are then selected
// in that one bucket, each within what lies above the previous one, and must still be exact.
TEST(IntensityFeatures, RanksSharingOneBucketAreEachExact) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  for (size_t n : {12, 1001, 100003}) {
    std::vector<double> values(n);
    for (double& v : values) v = unit(rng);
    values[n / 3] = 1e12;
    std::vector<double> sorted = values;
    std::sort(sorted.begin(), sorted.end());
    auto at = [&](double p) {
      const double h = double(n - 1) * p;
      const size_t lo = size_t(std::floor(h)), hi = std::min(lo + 1, n - 1);
      return sorted[lo] + (h - double(lo)) * (sorted[hi] - sorted[lo]);
    };
    auto f = intensity_features(values);
    ASSERT_TRUE(f.ok());
    EXPECT_EQ(f->p10, at(0.1)) << n;
    EXPECT_EQ(f->median, at(0.5)) << n;
    EXPECT_EQ(f->p90, at(0.9)) << n;
    EXPECT_EQ(f->interquartile_range, at(0.75) - at(0.25)) << n;
  }
}

}  // namespace
}  // namespace soiq
