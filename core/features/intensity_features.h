#pragma once
// First-order intensity statistics of a list of values (docs/DESIGN.md "Features": intensity; IBSI-1
// chapter 3.3 "Intensity-based statistical features", no discretisation). The definitions are
// IBSI's, with population moments (divide by N), and reproduce the IBSI-1 digital phantom values of
// REFERENCE_VALUES.md:
//   mean (Q4LE) = sum x / N               variance (ECT3) = m2 = sum (x - mean)^2 / N
//   standard_deviation = sqrt(m2)         skewness (KE2A) = m3 / m2^(3/2)
//   excess_kurtosis (IPH6) = m4 / m2^2 - 3
//   median (Y12H), p10 (QG58), p90 (8DWT), interquartile_range (SALO) = p75 - p25: percentiles
//     interpolated linearly between order statistics, value at rank h = (N - 1) p (0-based), as
//     numpy.percentile's default and PyRadiomics do
//   minimum (1GSF), maximum (84IY), range (2OJQ) = max - min
//   mean_absolute_deviation (4FUA) = sum |x - mean| / N
//   energy (N8CA) = sum x^2               root_mean_square (5ZWQ) = sqrt(energy / N)
//   voxel_count = N
//
// Inputs   values: the intensities of a region (resample.h gives them), any order, all finite.
// Output   IntensityFeatures. A constant region (m2 == 0) has skewness and excess kurtosis 0, as
//          PyRadiomics returns, rather than 0/0.
// Errors   INVALID_ARGUMENT  no values ("no intensity values"); a NaN or infinite value.
// Cost     O(N): moments in two passes over doubles; the percentiles' order statistics, exact, by
//          one pass into up to 2^16 buckets monotone in the value and a selection (nth_element)
//          within the few buckets that hold a wanted rank (none in a bucket of one repeated value,
//          as binary and integer images give); no sort. Thread-safe.

#include <cstdint>
#include <vector>

#include "core/base/status.h"

namespace soiq {

struct IntensityFeatures {
  int64_t voxel_count = 0;
  double mean = 0, variance = 0, standard_deviation = 0, skewness = 0, excess_kurtosis = 0;
  double minimum = 0, maximum = 0, median = 0, p10 = 0, p90 = 0, interquartile_range = 0, range = 0;
  double mean_absolute_deviation = 0, energy = 0, root_mean_square = 0;
};

// Taken by value (callers move their samples in); the values are not reordered.
Result<IntensityFeatures> intensity_features(std::vector<double> values);

}  // namespace soiq
