#include "bench/cpu_affinity.h"

#include <sched.h>

#include <cstring>

namespace soiq::bench {

static_assert(sizeof(cpu_set_t) <= 128, "ScopedAffinity::saved_ is too small for cpu_set_t");

ScopedAffinity::ScopedAffinity(int cpu) {
  if (cpu < 0) return;
  cpu_set_t saved;
  if (sched_getaffinity(0, sizeof saved, &saved) != 0) return;
  std::memcpy(saved_, &saved, sizeof saved);
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(cpu, &one);
  pinned_ = sched_setaffinity(0, sizeof one, &one) == 0;
}

ScopedAffinity::~ScopedAffinity() {
  if (!pinned_) return;
  cpu_set_t saved;
  std::memcpy(&saved, saved_, sizeof saved);
  static_cast<void>(sched_setaffinity(0, sizeof saved, &saved));
}

}  // namespace soiq::bench
