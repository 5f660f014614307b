#pragma once
// `soiq-bench simgen --out DIR [--spacing S]`: writes the paper's simulated models
// (tests/support/simulated_models.h) as DIR/SMn_V1.nii.gz (V1, the analytic voxel-centre volume),
// DIR/SMn_S1.vtp (S1, marching cubes of V1) and DIR/models.tsv. Returns the process exit code.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_simgen(const CliArgs& args);

}  // namespace soiq::bench
