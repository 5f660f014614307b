#include "core/voxelize/crossing_buffers.h"

#include <mutex>

namespace soiq {

namespace {

// At most this many idle buffers are kept: one per share of the largest thread counts in use.
constexpr size_t kKeptBuffers = 16;

std::mutex& pool_mutex() {
  static std::mutex m;
  return m;
}

std::vector<std::unique_ptr<std::vector<LineCrossingAt>>>& pool() {
  static auto* p = new std::vector<std::unique_ptr<std::vector<LineCrossingAt>>>();  // never destroyed
  return *p;
}

}  // namespace

CrossingBufferLease::CrossingBufferLease() {
  {
    std::lock_guard<std::mutex> lock(pool_mutex());
    if (!pool().empty()) {
      buffer_ = std::move(pool().back());
      pool().pop_back();
    }
  }
  if (!buffer_) buffer_ = std::make_unique<std::vector<LineCrossingAt>>();
}

CrossingBufferLease::~CrossingBufferLease() {
  if (!buffer_ || buffer_->capacity() > kKeptCrossings) return;
  buffer_->clear();
  std::lock_guard<std::mutex> lock(pool_mutex());
  if (pool().size() < kKeptBuffers) pool().push_back(std::move(buffer_));
}

}  // namespace soiq
