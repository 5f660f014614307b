#include "core/intensity_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace soiq {
namespace {

// The order statistics of the given ranks (ascending, distinct, each < N), exactly those a sort
// would put there, by one bucket pass: bucket(v) = floor((v - min) * scale) is non-decreasing in v
// (each rounded step is monotone), so bucket(v) < bucket(w) implies v < w, and the value of rank k
// is the (k - values in lower buckets)-th smallest of k's bucket. Only the buckets holding a rank
// are gathered and selected (nth_element). O(N + buckets) for the at most ten ranks used here.
std::vector<double> order_statistics(const std::vector<double>& v, const std::vector<size_t>& ranks, double lo,
                                     double hi) {
  std::vector<double> out(ranks.size(), lo);
  if (!(hi > lo)) return out;  // constant values
  const size_t buckets = std::clamp<size_t>(v.size() / 8, 1, size_t(1) << 16);
  // A finite scale even when hi - lo overflows (then every value falls in bucket 0: still exact).
  const double width = hi - lo;
  double scale = double(buckets) / width;
  if (!std::isfinite(width) || !std::isfinite(scale)) scale = 0;
  // Through int64_t: a signed conversion is one instruction; (x - lo) * scale is in [0, buckets].
  auto bucket_of = [&](double x) { return std::min(size_t(int64_t((x - lo) * scale)), buckets - 1); };
  std::vector<uint32_t> count(buckets, 0);
  for (const double x : v) ++count[bucket_of(x)];
  // The bucket of each rank and its rank within that bucket.
  std::vector<size_t> rank_bucket(ranks.size()), rank_within(ranks.size());
  std::vector<int> slot(buckets, -1);
  std::vector<std::vector<double>> gathered;
  size_t below = 0, r = 0;
  for (size_t b = 0; b < buckets && r < ranks.size(); ++b) {
    while (r < ranks.size() && ranks[r] < below + count[b]) {
      if (slot[b] < 0) slot[b] = int(gathered.size()), gathered.emplace_back();
      rank_bucket[r] = b, rank_within[r] = ranks[r] - below;
      ++r;
    }
    below += count[b];
  }
  for (size_t b = 0; b < buckets; ++b) {
    if (slot[b] >= 0) gathered[size_t(slot[b])].reserve(count[b]);
  }
  for (const double x : v) {
    const int s = slot[bucket_of(x)];
    if (s >= 0) gathered[size_t(s)].push_back(x);
  }
  for (size_t q = 0; q < ranks.size(); ++q) {
    std::vector<double>& g = gathered[size_t(slot[rank_bucket[q]])];
    std::nth_element(g.begin(), g.begin() + long(rank_within[q]), g.end());
    out[q] = g[rank_within[q]];
  }
  return out;
}

// Linear interpolation between order statistics at 0-based rank h = (N - 1) p ("type 7").
double percentile(size_t n, const std::vector<size_t>& ranks, const std::vector<double>& values, double p) {
  const double h = double(n - 1) * p;
  const size_t lo = size_t(std::floor(h));
  const size_t hi = std::min(lo + 1, n - 1);
  auto at = [&](size_t rank) {
    return values[size_t(std::lower_bound(ranks.begin(), ranks.end(), rank) - ranks.begin())];
  };
  return at(lo) + (h - double(lo)) * (at(hi) - at(lo));
}

constexpr double kPercentiles[] = {0.1, 0.25, 0.5, 0.75, 0.9};

}  // namespace

Result<IntensityFeatures> intensity_features(std::vector<double> values) {
  if (values.empty()) return invalid_argument("no intensity values: the region has no voxel inside the image");
  IntensityFeatures f;
  const double n = double(values.size());
  f.voxel_count = int64_t(values.size());

  // One pass for the sums and the extremes. A NaN or infinity makes a sum non-finite, so the
  // per-value check runs only then (or when finite values overflow the energy).
  double sum = 0, energy = 0, lo = values[0], hi = values[0];
  for (double v : values) {
    sum += v;
    energy += v * v;
    lo = v < lo ? v : lo;
    hi = v >= hi ? v : hi;  // the last maximum, as std::minmax_element
  }
  if (!std::isfinite(sum) || !std::isfinite(energy)) {
    for (double v : values) {
      if (!std::isfinite(v)) return invalid_argument("intensity values include NaN or infinity");
    }
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

  f.minimum = lo;
  f.maximum = hi;
  f.range = f.maximum - f.minimum;
  std::vector<size_t> ranks;
  for (const double p : kPercentiles) {
    const size_t lo = size_t(std::floor(double(values.size() - 1) * p));
    ranks.push_back(lo);
    if (lo + 1 < values.size()) ranks.push_back(lo + 1);
  }
  std::sort(ranks.begin(), ranks.end());
  ranks.erase(std::unique(ranks.begin(), ranks.end()), ranks.end());
  const std::vector<double> ordered = order_statistics(values, ranks, f.minimum, f.maximum);
  const size_t count = values.size();
  f.median = percentile(count, ranks, ordered, 0.5);
  f.p10 = percentile(count, ranks, ordered, 0.1);
  f.p90 = percentile(count, ranks, ordered, 0.9);
  f.interquartile_range = percentile(count, ranks, ordered, 0.75) - percentile(count, ranks, ordered, 0.25);
  return f;
}

}  // namespace soiq
