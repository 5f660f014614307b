#pragma once
// One cell of a benchmark table: prepare a method (untimed), time it (single-thread runs pinned to
// one CPU), and compare its mask with a reference mask.

#include <string>
#include <vector>

#include "bench/conversion.h"
#include "bench/mask_agreement.h"
#include "bench/timing.h"

namespace soiq::bench {

struct MethodRun {
  Timed timed;
  Agreement vs_reference;  // against the mask the table compares with (V1, or our 1d result)
};

// `pin_cpu` < 0: never pin. The error names the method.
Result<MethodRun> run_method(Method method, const TriangleMesh& mesh, const Mask& reference, int threads, int runs,
                             int pin_cpu);

// The same for several methods on one mesh, timed in rounds (one run of each per round, in order),
// so that on a shared machine every method sees the same conditions. Single-thread methods are
// pinned to `pin_cpu` during their runs. A method's failure is its own cell's error. A method
// stops taking part once its runs have used `budget_ms` (slow peers on big grids).
struct MethodSpec {
  Method method;
  int threads = 1;
};
std::vector<Result<MethodRun>> run_methods_interleaved(const std::vector<MethodSpec>& specs, const TriangleMesh& mesh,
                                                       const Mask& reference, int runs, int pin_cpu,
                                                       double budget_ms = 20000);

// "12.3" (best of the runs, ms) or "n/a"; the table's time cell. The best rather than the
// median: on a shared virtual machine the noise only ever adds time.
std::string time_cell(const Result<MethodRun>& r);
// "1.000000 (0)": IoU against the reference and differing voxels, or "n/a".
std::string agreement_cell(const Result<MethodRun>& r);

}  // namespace soiq::bench
