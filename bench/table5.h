#pragma once
// `soiq-bench table5 --models DIR [--runs N] [--threads T] [--pin CPU]`: the paper's Table 5 on
// the simulated models written by `simgen` (DIR/SMn_S1.vtp converted onto the grid of
// DIR/SMn_V1.nii.gz), in one process: best ms of 1d (1 thread), 1d (T threads), 2d, vtk-stencil
// and the optional peers built in (itk, cgal, openvdb: one column each, and its time against 1d),
// then IoU against V1 with the number of differing voxels for each. Single-thread runs are pinned
// to CPU `--pin` (default 0; -1 disables). Prints markdown.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_table5(const CliArgs& args);

}  // namespace soiq::bench
