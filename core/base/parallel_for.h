#pragma once
// Runs body(begin, end) over [0, n) split into at most `threads` contiguous chunks of at least
// `min_chunk`, the first on the caller and the others on core's worker pool (run_tasks.h). With
// threads <= 1 or small n it is a plain call. Chunks are contiguous and fixed, so any per-chunk
// output can be concatenated in order and the result never depends on the thread count.

#include <algorithm>
#include <cstdint>

#include "core/base/run_tasks.h"

namespace soiq {

template <typename Body>
void parallel_for(int64_t n, int threads, Body&& body, int64_t min_chunk = 4096) {
  const int64_t chunks = std::clamp<int64_t>(n / std::max<int64_t>(min_chunk, 1), 1, std::max(threads, 1));
  if (chunks <= 1) {
    body(int64_t(0), n);
    return;
  }
  run_tasks(chunks, int(chunks), [&](int64_t c) { body(n * c / chunks, n * (c + 1) / chunks); });
}

}  // namespace soiq
