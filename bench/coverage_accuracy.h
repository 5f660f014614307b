#pragma once
// The accuracy tables of `soiq-bench coverage` (coverage_bench.h), as Markdown:
//  - analytic volume: oblique sphere, ellipsoid and cube on an oblique anisotropic grid, the sum of
//    the fractions against the polyhedron's exact volume at n = 1, 2, 4, 8 lines per voxel side;
//  - a 1 cm lesion (radius 5 mm) in two uptake fields whose mean over the lesion is known exactly
//    (a linear gradient; a peak 1 + 10 (1 - r^2/R^2), mean 5), on 2, 4 and 6 mm voxels at 64
//    sub-voxel positions: the centre rule's mean and the coverage-weighted mean against it;
//  - the STS tumours (CT masks, smoothed as segmentation tools export surfaces) on their own PET
//    series (SUVbw): mean uptake by the centre rule and weighted, and the volumes.

#include <string>

#include "core/base/status.h"

namespace soiq::bench {

Status print_volume_accuracy();
Status print_lesion_accuracy();
// `sts_dir`: tests/data/sts (each patient's CT_mask.nii.gz and dicom_jpegls/PET/).
Status print_sts_pet_uptake(const std::string& sts_dir);

}  // namespace soiq::bench
