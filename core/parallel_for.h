#pragma once
// Runs body(begin, end) over [0, n) split into `threads` contiguous chunks, one std::thread per
// chunk beyond the first (which runs on the caller). With threads <= 1 or small n it is a plain
// call. Chunks are contiguous and fixed, so any per-chunk output can be concatenated in order and
// the result never depends on the thread count.

#include <algorithm>
#include <cstdint>
#include <thread>
#include <vector>

namespace soiq {

template <typename Body>
void parallel_for(int64_t n, int threads, Body&& body, int64_t min_chunk = 4096) {
  const int64_t chunks = std::clamp<int64_t>(n / std::max<int64_t>(min_chunk, 1), 1, std::max(threads, 1));
  if (chunks <= 1) {
    body(int64_t(0), n);
    return;
  }
  std::vector<std::thread> pool;
  for (int64_t c = 1; c < chunks; ++c)
    pool.emplace_back([&body, c, n, chunks] { body(n * c / chunks, n * (c + 1) / chunks); });
  body(int64_t(0), n / chunks);
  for (auto& t : pool) t.join();
}

}  // namespace soiq
