#pragma once
// soiq-bench coverage --models DIR [--sts DIR] [--runs N] [--pin CPU]: the cost of coverage fractions
// (core/voxelize/coverage_1d.h) beside the plain 1D method on the simulated models SM1, SM6 and
// SM11 (soiq-bench simgen), one thread, runs interleaved so that both see the same machine; each
// method to its own sparse output (runs, or runs plus partly covered voxels), as the service keeps
// them. Prints a Markdown table.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_coverage_bench(const CliArgs& args);

}  // namespace soiq::bench
