#pragma once
// `soiq-bench features --models DIR [--sts DIR] [--runs N]`: the time per structure of the full
// feature set, split into the conversion (1D method, dense mask not built) and the parts
// structure_features reports (volume shape, the mask-surface sweep of the runs, surface shape of
// the stored surface and of the mask surface, 2D diameters, regions, resampling, intensity), best
// of N each; conversion and features alternate run by run so both see the same load. Structures: SM1-SM11 from DIR (S1
// as the stored surface on V1's grid, intensity on a synthetic ramp image, inside and in a 3 mm shell) and, with --sts,
// the tumour masks of DIR/STS_xxx/CT_mask.nii.gz (intensity on DIR/STS_xxx/PET_image.nii.gz where it exists, inside and
// in a 5 mm shell). Prints a markdown table.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_features_bench(const CliArgs& args);

}  // namespace soiq::bench
