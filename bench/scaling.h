#pragma once
// `soiq-bench scaling [--runs N] [--threads T] [--pin CPU]`: UV spheres (radius 40 mm) of 1k to 1M
// triangles on grids of 1 mm and 0.25 mm around them; best ms of 1d with 1 and T threads and of
// vtk-stencil, and vtk-stencil's differing voxels against 1d. Single-thread runs are pinned.
// Prints markdown.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_scaling(const CliArgs& args);

}  // namespace soiq::bench
