#include "core/features/intensity_features.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/cpu_dispatch.h"

namespace soiq {
namespace {

// Buckets monotone in the value: bucket(v) = floor((v - lo) * scale) is non-decreasing in v (each
// rounded step is monotone), so bucket(v) < bucket(w) implies v < w.
class Buckets {
 public:
  Buckets(size_t n, double lo, double hi) : lo_(lo), count_(std::clamp<size_t>(n / 8, 1, size_t(1) << 16)) {
    // A finite scale even when hi - lo overflows (then every value falls in bucket 0: still exact).
    const double width = hi - lo;
    scale_ = double(count_) / width;
    if (!(hi > lo) || !std::isfinite(width) || !std::isfinite(scale_)) scale_ = 0;
  }
  size_t size() const { return count_; }
  // (x - lo) * scale is in [0, buckets], or NaN when a range wider than a double made the scale 0
  // and x - lo is infinite: converting NaN (or anything out of range) to an integer is undefined,
  // so both ends are decided by comparisons first (NaN fails every one: bucket 0).
  uint16_t of(double x) const {
    const double t = (x - lo_) * scale_;
    if (!(t >= 1)) return 0;
    if (t >= double(count_ - 1)) return uint16_t(count_ - 1);
    return uint16_t(int64_t(t));
  }

 private:
  double lo_, scale_ = 0;
  size_t count_;
};

// The order statistics of the given ranks (ascending, distinct, each < N), exactly those a sort
// would put there: the value of rank k is the (k - values in lower buckets)-th smallest of k's
// bucket. Only the buckets holding a rank are gathered and selected (nth_element): O(N + buckets)
// for the at most ten ranks used here. `bucket` and `count` are the values' buckets and their sizes.
std::vector<double> order_statistics(const std::vector<double>& v, const std::vector<uint16_t>& bucket,
                                     const std::vector<uint32_t>& count, const std::vector<size_t>& ranks) {
  std::vector<double> out(ranks.size());
  // The bucket of each rank and its rank within that bucket.
  std::vector<size_t> rank_bucket(ranks.size()), rank_within(ranks.size());
  std::vector<int> slot(count.size(), -1);
  std::vector<std::vector<double>> gathered;
  size_t below = 0, r = 0;
  for (size_t b = 0; b < count.size() && r < ranks.size(); ++b) {
    while (r < ranks.size() && ranks[r] < below + count[b]) {
      if (slot[b] < 0) slot[b] = int(gathered.size()), gathered.emplace_back();
      rank_bucket[r] = b, rank_within[r] = ranks[r] - below;
      ++r;
    }
    below += count[b];
  }
  for (size_t b = 0; b < count.size(); ++b) {
    if (slot[b] >= 0) gathered[size_t(slot[b])].reserve(count[b]);
  }
  for (size_t i = 0; i < v.size(); ++i) {
    const int s = slot[bucket[i]];
    if (s >= 0) gathered[size_t(s)].push_back(v[i]);
  }
  // A bucket of one repeated value (binary or integer images put every value in its own bucket)
  // needs no selection; otherwise ranks are selected in ascending order, each within what lies
  // above the previous one of its bucket, so ten ranks in one bucket do not cost ten full passes.
  std::vector<size_t> selected_below(gathered.size(), 0);
  std::vector<uint8_t> constant(gathered.size(), 0);
  for (size_t b = 0; b < gathered.size(); ++b) {
    const auto [lo, hi] = std::minmax_element(gathered[b].begin(), gathered[b].end());
    constant[b] = *lo == *hi ? 1 : 0;
  }
  for (size_t q = 0; q < ranks.size(); ++q) {
    const size_t b = size_t(slot[rank_bucket[q]]);
    std::vector<double>& g = gathered[b];
    if (!constant[b]) {
      std::nth_element(g.begin() + long(selected_below[b]), g.begin() + long(rank_within[q]), g.end());
      selected_below[b] = rank_within[q] + 1;
    }
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

static Result<IntensityFeatures> intensity_features_here(std::vector<double> values) {
  if (values.empty()) return invalid_argument("no intensity values: the region has no voxel inside the image");
  IntensityFeatures f;
  const double n = double(values.size());
  f.voxel_count = int64_t(values.size());

  // Each pass keeps kLanes independent partial sums (values i, i + kLanes, ...): one chain of
  // dependent additions per sum would bound the pass by the adder's latency. The partial sums are
  // added in a fixed order, so the result depends on the values' order only, as before.
  constexpr size_t kLanes = 4;
  const size_t count = values.size(), whole = count / kLanes * kLanes;
  // One pass for the sums and the extremes. A NaN or infinity makes a sum non-finite, so the
  // per-value check runs only then (or when finite values overflow the energy).
  double sum[kLanes] = {}, squares[kLanes] = {}, low[kLanes], high[kLanes];
  for (size_t l = 0; l < kLanes; ++l) low[l] = high[l] = values[0];
  auto first_pass = [&](size_t l, double v) {
    sum[l] += v;
    squares[l] += v * v;
    low[l] = v < low[l] ? v : low[l];
    high[l] = v > high[l] ? v : high[l];
  };
  for (size_t i = 0; i < whole; i += kLanes) {
    for (size_t l = 0; l < kLanes; ++l) first_pass(l, values[i + l]);
  }
  for (size_t i = whole; i < count; ++i) first_pass(i - whole, values[i]);
  auto add = [](const double(&s)[kLanes]) { return (s[0] + s[1]) + (s[2] + s[3]); };
  const double total = add(sum), energy = add(squares);
  const double lo = std::min({low[0], low[1], low[2], low[3]}), hi = std::max({high[0], high[1], high[2], high[3]});
  if (!std::isfinite(total) || !std::isfinite(energy)) {
    for (double v : values) {
      if (!std::isfinite(v)) return invalid_argument("intensity values include NaN or infinity");
    }
  }
  f.mean = total / n;
  // Central moments in a second pass (one pass, E[x^2] - mean^2, cancels badly for CT-like
  // values), which also sorts the values into the percentiles' buckets.
  const Buckets buckets(count, lo, hi);
  std::vector<uint16_t> bucket(count);
  std::vector<uint32_t> bucket_size(buckets.size(), 0);
  double m2s[kLanes] = {}, m3s[kLanes] = {}, m4s[kLanes] = {}, mads[kLanes] = {};
  auto second_pass = [&](size_t l, size_t i) {
    const double d = values[i] - f.mean;
    const double d2 = d * d;
    m2s[l] += d2;
    m3s[l] += d2 * d;
    m4s[l] += d2 * d2;
    mads[l] += std::abs(d);
    bucket[i] = buckets.of(values[i]);
  };
  for (size_t i = 0; i < whole; i += kLanes) {
    for (size_t l = 0; l < kLanes; ++l) second_pass(l, i + l);
  }
  for (size_t i = whole; i < count; ++i) second_pass(i - whole, i);
  for (const uint16_t b : bucket) ++bucket_size[b];
  const double m2 = add(m2s) / n, m3 = add(m3s) / n, m4 = add(m4s) / n;
  f.variance = m2;
  f.standard_deviation = std::sqrt(m2);
  f.skewness = m2 > 0 ? m3 / std::pow(m2, 1.5) : 0.0;
  f.excess_kurtosis = m2 > 0 ? m4 / (m2 * m2) - 3.0 : 0.0;
  f.mean_absolute_deviation = add(mads) / n;
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
  const std::vector<double> ordered = order_statistics(values, bucket, bucket_size, ranks);
  f.median = percentile(count, ranks, ordered, 0.5);
  f.p10 = percentile(count, ranks, ordered, 0.1);
  f.p90 = percentile(count, ranks, ordered, 0.9);
  f.interquartile_range = percentile(count, ranks, ordered, 0.75) - percentile(count, ranks, ordered, 0.25);
  return f;
}

// Compiled for the CPU it runs on (core/base/cpu_dispatch.h).
Result<IntensityFeatures> intensity_features(std::vector<double> values) {
  return cpu_dispatch([&] { return intensity_features_here(std::move(values)); });
}

}  // namespace soiq
