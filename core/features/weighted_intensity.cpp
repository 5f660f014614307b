#include "core/features/weighted_intensity.h"

#include <cmath>
#include <string>

namespace soiq {

Result<WeightedIntensity> weighted_intensity(const std::vector<double>& values, const std::vector<double>& weights,
                                             double voxel_volume_mm3) {
  if (values.empty()) return invalid_argument("no intensity values");
  if (values.size() != weights.size()) {
    return invalid_argument(std::to_string(values.size()) + " values for " + std::to_string(weights.size()) +
                            " weights");
  }
  double w_sum = 0, wx = 0, wxx = 0;
  for (size_t n = 0; n < values.size(); ++n) {
    const double w = weights[n], x = values[n];
    if (!(w > 0 && w <= 1)) return invalid_argument("weight " + std::to_string(w) + " is outside (0, 1]");
    if (!std::isfinite(x)) return invalid_argument("intensity values must be finite");
    w_sum += w;
    wx += w * x;
    wxx += w * x * x;
  }
  WeightedIntensity f;
  f.voxel_count = w_sum;
  f.mean = wx / w_sum;
  // Second pass about the mean: sum w x^2 - W mean^2 cancels badly for CT's large offsets.
  double m2 = 0;
  for (size_t n = 0; n < values.size(); ++n) {
    const double d = values[n] - f.mean;
    m2 += weights[n] * d * d;
  }
  f.variance = m2 / w_sum;
  f.standard_deviation = std::sqrt(f.variance);
  f.root_mean_square = std::sqrt(wxx / w_sum);
  f.integrated_intensity = wx * voxel_volume_mm3;
  return f;
}

}  // namespace soiq
