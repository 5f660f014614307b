#include "bench/cpu_probe.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "bench/clock.h"

namespace soiq::bench {

namespace {

// A dependency chain of multiply-adds: compute-bound, cache-resident, ~1.5 ns per step.
// noinline: both threads must run the same machine code. Inlined into run_cpu_probe, GCC 12 gave
// the main thread's copy a loop 2.5x slower than the helper's, and the probe reported 0.79x (and
// 1.07-1.26x in earlier runs) on a machine whose two cores scale 1.99x.
__attribute__((noinline)) double kernel(long steps, double seed) {
  double s = seed;
  for (long i = 0; i < steps; ++i) s = s * 0.9999999 + 1e-7 * double(i & 7);
  return s;
}

}  // namespace

int run_cpu_probe(const CliArgs& args) {
  const Result<int> runs = args.get_int("--runs", 5);
  if (!runs.ok() || *runs < 1) {
    std::fprintf(stderr, "usage: soiq-bench cpu-probe [--runs N]\n");
    return 2;
  }
  constexpr long kSteps = 40'000'000;
  double one = 1e300, two = 1e300, sink = 0;
  for (int r = 0; r < *runs; ++r) {
    auto t0 = Clock::now();
    sink += kernel(kSteps, r);
    one = std::min(one, ms_since(t0));
    t0 = Clock::now();
    double other = 0;
    std::thread helper([&other, r] { other = kernel(kSteps / 2, r + 0.5); });
    sink += kernel(kSteps / 2, r);
    helper.join();
    sink += other;
    two = std::min(two, ms_since(t0));
  }
  std::printf("parallel capacity: %.1f ms on 1 thread, %.1f ms split over 2 threads: %.2fx (ideal 2.00x)%s\n", one, two,
              one / two, sink == 0.123 ? " " : "");
  return 0;
}

}  // namespace soiq::bench
