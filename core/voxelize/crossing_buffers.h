#pragma once
// Crossing buffers that outlive a conversion. The threads of a multi-threaded 1D conversion each
// collect the crossings of their share of the triangles in a buffer of a megabyte or so; a fresh
// one per conversion came from mmap (or a trimmed arena) each time, and its page faults cost as
// much as the walk. A lease takes a buffer from a process-wide pool and gives it back emptied, its
// capacity kept, unless it grew past kKeptCrossings: memory a large conversion was admitted for
// must not stay held after it. Thread-safe (one mutex round trip per lease and return). Internal
// to core/voxelize.

#include <cstddef>
#include <memory>
#include <vector>

#include "core/voxelize/line_fill.h"

namespace soiq {

class CrossingBufferLease {
 public:
  static constexpr size_t kKeptCrossings = size_t(1) << 20;

  CrossingBufferLease();
  ~CrossingBufferLease();
  CrossingBufferLease(CrossingBufferLease&&) noexcept = default;
  CrossingBufferLease& operator=(CrossingBufferLease&&) noexcept = default;

  std::vector<LineCrossingAt>& operator*() { return *buffer_; }
  std::vector<LineCrossingAt>* operator->() { return buffer_.get(); }

 private:
  std::unique_ptr<std::vector<LineCrossingAt>> buffer_;
};

}  // namespace soiq
