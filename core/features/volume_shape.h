#pragma once
// Shape features of a volume model computed from its voxel centres (docs/DESIGN.md "Features"; IBSI
// "Morphological features": YEKZ approximate volume, TDIC/P9VJ/7J51 major/minor/least axis
// length, Q3CK elongation, N17B flatness; PyRadiomics VoxelVolume, Major/Minor/LeastAxisLength,
// Elongation, Flatness).
//
// Inputs   a RunLengthVolume on a valid grid (any direction matrix).
// Output   over the N inside voxels, with p_n = the LPS centre of voxel n (direction applied):
//            voxel_count          N
//            voxel_volume_mm3     N * spacing_x * spacing_y * spacing_z
//            centroid_mm          mean of p_n
//            bbox_min_mm/_max_mm  per LPS coordinate, min/max of p_n (centres, not voxel faces)
//            covariance_mm2       C = sum (p_n - centroid)(p_n - centroid)^T / d in LPS, with d = N
//                                 as PyRadiomics does (default), or d = N - 1 (`divisor`
//                                 kNMinus1) as the IBSI consensus values were computed: the
//                                 IBSI-1 phantom's minor/least axis lengths (N = 74) match only
//                                 with N - 1 (9.31 and 8.54 vs 9.245 and 8.478 with N)
//            eigenvalues_mm2      of C, descending: l1 >= l2 >= l3 >= 0
//            major/minor/least_axis_length_mm   4 sqrt(l1), 4 sqrt(l2), 4 sqrt(l3)
//            elongation           sqrt(l2 / l1);  flatness  sqrt(l3 / l1)
// Method   closed-form sums per run (sum of i and i^2 over [begin, end)), accumulated exactly in
//          128-bit integers in index space; the central moments N*S_ab - S_a*S_b are exact
//          integers, so the only rounding is the final division and the mapping to LPS
//          (C = A C_index A^T with A = direction * diag(spacing)). No dense mask is built.
// Errors   INVALID_ARGUMENT for an invalid geometry, a malformed volume (line_start of the wrong
//          size) or an empty volume (no inside voxel: the features are undefined).
// Cost     O(runs + lines), memory O(1). Thread-safe.
// Caveats  One voxel (l1 = 0) gives elongation and flatness NaN (0/0), as in PyRadiomics.
//          With kNMinus1, one voxel has a zero covariance (not 0/0).
//          Sums are exact while N^2 * (largest index)^2 < 2^126 (e.g. 1e9 voxels, indices < 1e9).

#include <cstdint>

#include "core/base/run_length_volume.h"
#include "core/base/status.h"
#include "core/base/vec3.h"

namespace soiq {

// What the covariance of the voxel centres is divided by.
enum class CovarianceDivisor {
  kN,        // population covariance: PyRadiomics (and the default)
  kNMinus1,  // sample covariance (numpy.cov's default): the IBSI reference values
};

struct VolumeShape {
  int64_t voxel_count = 0;
  double voxel_volume_mm3 = 0;
  Vec3 centroid_mm{0, 0, 0};
  Vec3 bbox_min_mm{0, 0, 0};
  Vec3 bbox_max_mm{0, 0, 0};
  Mat3 covariance_mm2{};
  Vec3 eigenvalues_mm2{0, 0, 0};
  double major_axis_length_mm = 0;
  double minor_axis_length_mm = 0;
  double least_axis_length_mm = 0;
  double elongation = 0;
  double flatness = 0;
};

Result<VolumeShape> volume_shape(const RunLengthVolume& volume, CovarianceDivisor divisor = CovarianceDivisor::kN);

}  // namespace soiq
