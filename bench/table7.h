#pragma once
// `soiq-bench table7 [--runs N] [--pin CPU]`: conversion time against mesh size, as the paper's
// Table 7: UV spheres (radius 20 mm) of increasing triangle count on a 0.5 mm grid around them
// (~86^3 voxels, small so the per-voxel peers finish), 1d vs the paper's 3D method (our oracle)
// vs vtkSelectEnclosedPoints, all single-threaded and pinned; each peer's differing voxels
// against 1d. Prints markdown.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_table7(const CliArgs& args);

}  // namespace soiq::bench
