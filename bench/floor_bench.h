#pragma once
// `soiq-bench floor --models DIR [--names SM1,SM6,SM11] [--runs N] [--pin CPU]`: the 1D method on
// one thread against the scanline floor (scanline_floor.h) on the same mesh, grid and CPU,
// alternating run by run so that both see the same machine, the least of N runs each; prints one
// markdown row per model: triangles, lattice points in the triangles' ranges, floor ms, 1d ms and
// their ratio. Models are DIR/<name>_S1.vtp on DIR/<name>_V1.nii.gz's grid (soiq-bench simgen).

#include "bench/cli_args.h"

namespace soiq::bench {

int run_floor_bench(const CliArgs& args);

}  // namespace soiq::bench
