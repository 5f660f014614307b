#pragma once
// `soiq-bench convert MESH --reference IMAGE --method M [--runs N] [--threads T] [--pin CPU]
//  [--json] [-o OUT]`: loads the mesh and the reference image's grid, prepares the method (both
// untimed), then times the conversion alone N times and prints min and median ms and the inside
// voxel count (one JSON object with --json). -o writes the mask of the last run. --pin pins a
// single-thread run to one CPU (T = 1 only).

#include "bench/cli_args.h"

namespace soiq::bench {

int run_convert(const CliArgs& args);

}  // namespace soiq::bench
