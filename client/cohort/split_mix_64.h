#pragma once
// SplitMix64 (Steele, Lea and Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014;
// the constants of Vigna's public-domain splitmix64.c): the one random generator of the synthetic
// cohorts. Tiny, and the same sequence on every machine and compiler, which std:: distributions do
// not promise; so a seed and a configuration give the same cohort, byte for byte, everywhere.
//
// next(): the next 64-bit value. uniform(lo, hi): a double in [lo, hi) from the top 53 bits.
// integer(lo, hi): an int in [lo, hi] (lo <= hi), by modulo (a bias below 2^-40 for the ranges used).
// Each call advances the state once. Not thread-safe: one generator per thread, or per patient.

#include <cstdint>

namespace soiq::cohort {

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}

  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) * 0x1.0p-53; }
  int integer(int lo, int hi) { return lo + int(next() % uint64_t(int64_t(hi) - lo + 1)); }

 private:
  uint64_t state_;
};

}  // namespace soiq::cohort
