#include "core/intensity_features.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace soiq {
namespace {

// Puts the order statistic of every rank in `ranks` (ascending, each in [first, last)) at its
// position, as a full sort would, by selection: nth_element on the middle rank partitions the range,
// and each side recurses with its own ranks. O(N log k) expected for k ranks instead of a sort's
// O(N log N); the values are the same.
void select_ranks(std::vector<double>& v, const size_t* ranks, size_t count, size_t first, size_t last) {
  if (count == 0) return;
  const size_t mid = count / 2, m = ranks[mid];
  std::nth_element(v.begin() + long(first), v.begin() + long(m), v.begin() + long(last));
  select_ranks(v, ranks, mid, first, m);
  select_ranks(v, ranks + mid + 1, count - mid - 1, m + 1, last);
}

// Linear interpolation between order statistics at 0-based rank h = (N - 1) p ("type 7"); the
// ranks floor(h) and floor(h) + 1 must be in place (select_ranks).
double percentile(const std::vector<double>& ordered, double p) {
  const double h = double(ordered.size() - 1) * p;
  const size_t lo = size_t(std::floor(h));
  const size_t hi = std::min(lo + 1, ordered.size() - 1);
  return ordered[lo] + (h - double(lo)) * (ordered[hi] - ordered[lo]);
}

constexpr double kPercentiles[] = {0.1, 0.25, 0.5, 0.75, 0.9};

}  // namespace

Result<IntensityFeatures> intensity_features(std::vector<double> values) {
  if (values.empty()) return invalid_argument("no intensity values: the region has no voxel inside the image");
  for (double v : values) {
    if (!std::isfinite(v)) return invalid_argument("intensity values include NaN or infinity");
  }
  IntensityFeatures f;
  const double n = double(values.size());
  f.voxel_count = int64_t(values.size());

  double sum = 0, energy = 0;
  for (double v : values) {
    sum += v;
    energy += v * v;
  }
  f.mean = sum / n;
  // Central moments in a second pass: one pass (E[x^2] - mean^2) cancels badly for CT-like values.
  double m2 = 0, m3 = 0, m4 = 0, mad = 0;
  for (double v : values) {
    const double d = v - f.mean;
    const double d2 = d * d;
    m2 += d2;
    m3 += d2 * d;
    m4 += d2 * d2;
    mad += std::abs(d);
  }
  m2 /= n;
  m3 /= n;
  m4 /= n;
  f.variance = m2;
  f.standard_deviation = std::sqrt(m2);
  f.skewness = m2 > 0 ? m3 / std::pow(m2, 1.5) : 0.0;
  f.excess_kurtosis = m2 > 0 ? m4 / (m2 * m2) - 3.0 : 0.0;
  f.mean_absolute_deviation = mad / n;
  f.energy = energy;
  f.root_mean_square = std::sqrt(energy / n);

  const auto [min_it, max_it] = std::minmax_element(values.begin(), values.end());
  f.minimum = *min_it;
  f.maximum = *max_it;
  f.range = f.maximum - f.minimum;
  std::vector<size_t> ranks;
  for (const double p : kPercentiles) {
    const size_t lo = size_t(std::floor(double(values.size() - 1) * p));
    ranks.push_back(lo);
    if (lo + 1 < values.size()) ranks.push_back(lo + 1);
  }
  std::sort(ranks.begin(), ranks.end());
  ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
  select_ranks(values, ranks.data(), ranks.size(), 0, values.size());
  f.median = percentile(values, 0.5);
  f.p10 = percentile(values, 0.1);
  f.p90 = percentile(values, 0.9);
  f.interquartile_range = percentile(values, 0.75) - percentile(values, 0.25);
  return f;
}

}  // namespace soiq
