#pragma once
// Intensity statistics weighted by each voxel's coverage fraction (docs/DESIGN.md "Coverage
// fractions", "Features"): a voxel half inside the surface counts half. With every weight 1 they
// are IBSI's unweighted statistics (intensity_features.h), to rounding.
//   voxel_count_w        W = sum w (the structure's volume in voxels, as sampled on the image)
//   mean_w               sum w x / W (the weighted arithmetic mean)
//   variance_w           sum w (x - mean_w)^2 / W: the weighted population variance with frequency
//                        weights (e.g. Cochran, "Sampling Techniques", 3rd ed. 1977, §2.11; GSL's
//                        gsl_stats_wvariance without its bias factor), which is IBSI's population
//                        variance (ECT3) when every w is 1. Not SlicerRT's sum of v^2 f^2: that is
//                        not a variance of anything.
//   standard_deviation_w sqrt(variance_w)
//   root_mean_square_w   sqrt(sum w x^2 / W) (IBSI 5ZWQ with weights)
//   integrated_intensity_w  voxel volume x sum w x: IBSI's integrated intensity (99N0, volume x mean)
//                        with the partial volume counted (for PET in SUV: the total lesion uptake)
// Percentiles, extremes and higher moments have no single weighted definition and are not given.
//
// Inputs   values and weights of equal length, weights in (0, 1], values finite; voxel_volume_mm3 > 0.
// Errors   INVALID_ARGUMENT  no values, lengths differ, a weight outside (0, 1], a non-finite value.
// Cost     O(N), two passes. Thread-safe.

#include <cstdint>
#include <vector>

#include "core/base/status.h"

namespace soiq {

struct WeightedIntensity {
  double voxel_count = 0;  // W
  double mean = 0, variance = 0, standard_deviation = 0, root_mean_square = 0, integrated_intensity = 0;
};

Result<WeightedIntensity> weighted_intensity(const std::vector<double>& values, const std::vector<double>& weights,
                                             double voxel_volume_mm3);

}  // namespace soiq
