#include "core/intensity_features.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace soiq {
namespace {

// Linear interpolation between order statistics at 0-based rank (N - 1) p ("type 7").
double percentile(const std::vector<double>& sorted, double p) {
  const double h = double(sorted.size() - 1) * p;
  const size_t lo = size_t(std::floor(h));
  const size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (h - double(lo)) * (sorted[hi] - sorted[lo]);
}

}  // namespace

Result<IntensityFeatures> intensity_features(std::vector<double> values) {
  if (values.empty()) return invalid_argument("no intensity values: the region has no voxel inside the image");
  for (double v : values) {
    if (!std::isfinite(v)) return invalid_argument("intensity values include NaN or infinity");
  }
  std::sort(values.begin(), values.end());
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

  f.minimum = values.front();
  f.maximum = values.back();
  f.range = f.maximum - f.minimum;
  f.median = percentile(values, 0.5);
  f.p10 = percentile(values, 0.1);
  f.p90 = percentile(values, 0.9);
  f.interquartile_range = percentile(values, 0.75) - percentile(values, 0.25);
  return f;
}

}  // namespace soiq
