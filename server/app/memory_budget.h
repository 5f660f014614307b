#pragma once
// One server-wide budget of bytes. Every conversion, feature computation, image upload and DICOM
// import estimates its peak bytes first (core/voxelize/memory_estimate.h, server/app/dicom_import_bytes.h) and
// reserves them here before it allocates: work is admitted by what it will hold, not by how many
// run, so twelve conversions of a 4e8-voxel grid queue instead of taking the machine down together.
//
// reserve(bytes, what, stop, advice)
//   Returns a Reservation that gives the bytes back when it goes. Waits, first come first served,
//   while others hold too much for `bytes` to fit; `stop` (may be empty) is polled every 50 ms
//   while waiting and its non-OK status ends the wait (cancel, deadline).
// Errors  RESOURCE_EXHAUSTED at once, without waiting, when `bytes` alone exceed the budget: the
//         message gives `what`, the estimate and the limit ("soiqd --memory-budget"), then `advice`
//         (what the client can change; by default a conversion's: spacing, margin, region).
// Thread-safety: all members may be called from any thread.
//
// The decoded-object caches (FeatureEngine's surfaces and images) are inside the budget too: a
// budget built with `cache_bytes` sets that much aside for them and admits work against the rest,
// so what soiqd holds, working or caching, stays under --memory-budget.

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::server {

// A `stop` for a reservation asked while the caller already holds others (the SEGs of a study
// before the next one): waiting on while holding could wait forever for work that waits on the
// caller, so after `patience` of waiting it gives up, RESOURCE_EXHAUSTED saying `why`. Until then,
// and when `holding` is false, it is `stop`.
std::function<Status()> stop_when_held_too_long(std::function<Status()> stop, bool holding, int patience_ms,
                                                std::string why);

// The share of a budget of `budget_bytes` that soiqd sets aside for its decoded-object caches: a
// quarter, at most 2 GiB (decoding a stored blob costs milliseconds; past a few GiB the hit rate of a
// query's working set no longer grows).
int64_t decoded_cache_share(int64_t budget_bytes);

class MemoryBudget {
 public:
  class Reservation {
   public:
    Reservation() = default;
    Reservation(Reservation&& other) noexcept : budget_(other.budget_), bytes_(other.bytes_) {
      other.budget_ = nullptr;
    }
    Reservation& operator=(Reservation&& other) noexcept;
    Reservation(const Reservation&) = delete;
    Reservation& operator=(const Reservation&) = delete;
    ~Reservation() { release(); }
    int64_t bytes() const { return bytes_; }
    // Gives back all but `bytes` (when the work's peak is over and only its result stays held);
    // never grows the reservation.
    void shrink_to(int64_t bytes);

   private:
    friend class MemoryBudget;
    Reservation(MemoryBudget* budget, int64_t bytes) : budget_(budget), bytes_(bytes) {}
    void release();
    MemoryBudget* budget_ = nullptr;
    int64_t bytes_ = 0;
  };

  // `cache_bytes` (at most `limit_bytes`) of the limit are set aside for the decoded-object caches.
  explicit MemoryBudget(int64_t limit_bytes, int64_t cache_bytes = 0);
  MemoryBudget(const MemoryBudget&) = delete;
  MemoryBudget& operator=(const MemoryBudget&) = delete;

  Result<Reservation> reserve(int64_t bytes, const std::string& what, const std::function<Status()>& stop = {},
                              const std::string& advice =
                                  "use a coarser spacing, a smaller margin or region, or "
                                  "raise the budget");

  int64_t limit() const { return limit_; }
  // What the caches may hold, and what is left for work.
  int64_t cache_bytes() const { return cache_bytes_; }
  int64_t work_limit() const { return limit_ - cache_bytes_; }
  int64_t in_use() const;
  // The largest number of bytes held at once since start (for tests and `soiq info`).
  int64_t peak() const;
  // How many reservations are waiting their turn now.
  int64_t waiting() const;

 private:
  void give_back(int64_t bytes);
  void skip_abandoned();  // with mutex_ held

  const int64_t limit_;
  const int64_t cache_bytes_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  int64_t in_use_ = 0;
  int64_t peak_ = 0;
  uint64_t next_ticket_ = 0;  // first come, first served: a large request is not starved by small ones
  uint64_t serving_ = 0;
  std::vector<uint64_t> abandoned_;  // tickets whose waiter stopped before being served
};

}  // namespace soiq::server
