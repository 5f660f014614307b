#pragma once
// Runs a prepared conversion up to N times and keeps the minimum and median wall time (steady
// clock) and the last result. Stops early, after at least one run, once the runs so far took
// `budget_ms` in total (slow peers on big grids); `runs` in the result says how many were made.

#include "bench/conversion.h"
#include "core/base/image.h"
#include "core/base/status.h"

namespace soiq::bench {

struct Timed {
  double min_ms = 0;
  double median_ms = 0;
  int runs = 0;
  Mask mask;  // the result of the last run
};

// INVALID_ARGUMENT when runs < 1; the conversion's own Status when it fails.
Result<Timed> time_conversion(const Conversion& conversion, int runs, double budget_ms = 20000);

}  // namespace soiq::bench
