#pragma once
// `soiq-bench cpu-probe [--runs N]`: how much a second thread can give on this machine right now.
// A fixed, purely arithmetic kernel (no memory traffic, no shared data) runs on one thread, then
// split over two; the best of N of each and their ratio are printed. On a dedicated 2-core machine
// the ratio is ~2.0; on a shared virtual machine it is whatever the host grants, and it bounds
// every multi-threaded figure measured in the same run.

#include "bench/cli_args.h"

namespace soiq::bench {

int run_cpu_probe(const CliArgs& args);

}  // namespace soiq::bench
