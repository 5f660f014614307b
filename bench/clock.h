#pragma once
// The benchmarks' wall clock: steady (never adjusted), with elapsed times as doubles.

#include <chrono>

namespace soiq::bench {

using Clock = std::chrono::steady_clock;

// Milliseconds since `start`.
inline double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Seconds since `start`.
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace soiq::bench
