#pragma once
// Pins the calling process to one CPU for the lifetime of the object and restores the previous
// affinity afterwards, so single-thread timings are taken on one core (as `taskset -c 0` would)
// while multi-thread runs of the same table use every core. A no-op when cpu < 0 or when the
// kernel refuses (the table then says "unpinned").

namespace soiq::bench {

class ScopedAffinity {
 public:
  explicit ScopedAffinity(int cpu);
  ~ScopedAffinity();
  ScopedAffinity(const ScopedAffinity&) = delete;
  ScopedAffinity& operator=(const ScopedAffinity&) = delete;
  bool pinned() const { return pinned_; }

 private:
  bool pinned_ = false;
  alignas(8) unsigned char saved_[128];  // a cpu_set_t, kept opaque so <sched.h> stays in the .cpp
};

}  // namespace soiq::bench
