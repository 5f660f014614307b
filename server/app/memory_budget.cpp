#include "server/app/memory_budget.h"

#include <algorithm>
#include <chrono>

#include "core/voxelize/memory_estimate.h"

namespace soiq::server {

int64_t decoded_cache_share(int64_t budget_bytes) { return std::clamp<int64_t>(budget_bytes / 4, 0, int64_t(2) << 30); }

MemoryBudget::MemoryBudget(int64_t limit_bytes, int64_t cache_bytes)
    : limit_(limit_bytes), cache_bytes_(std::clamp<int64_t>(cache_bytes, 0, std::max<int64_t>(limit_bytes, 0))) {}

MemoryBudget::Reservation& MemoryBudget::Reservation::operator=(Reservation&& other) noexcept {
  if (this != &other) {
    release();
    budget_ = other.budget_;
    bytes_ = other.bytes_;
    other.budget_ = nullptr;
  }
  return *this;
}

void MemoryBudget::Reservation::shrink_to(int64_t bytes) {
  bytes = std::max<int64_t>(bytes, 0);
  if (budget_ == nullptr || bytes >= bytes_) return;
  budget_->give_back(bytes_ - bytes);
  bytes_ = bytes;
}

void MemoryBudget::Reservation::release() {
  if (budget_) budget_->give_back(bytes_);
  budget_ = nullptr;
}

Result<MemoryBudget::Reservation> MemoryBudget::reserve(int64_t bytes, const std::string& what,
                                                        const std::function<Status()>& stop,
                                                        const std::string& advice) {
  bytes = std::max<int64_t>(bytes, 0);
  if (bytes > work_limit()) {
    const std::string budget = cache_bytes_ == 0
                                   ? "soiqd's memory budget of " + human_bytes(limit_)
                                   : "the " + human_bytes(work_limit()) + " that soiqd's memory budget of " +
                                         human_bytes(limit_) + " leaves beside " + human_bytes(cache_bytes_) +
                                         " of decoded-object caches";
    return resource_exhausted(what + " needs an estimated " + human_bytes(bytes) + ", more than " + budget +
                              " (soiqd --memory-budget): " + advice);
  }
  std::unique_lock<std::mutex> lock(mutex_);
  const uint64_t ticket = next_ticket_++;
  while (!(serving_ == ticket && in_use_ + bytes <= work_limit())) {
    if (stop) {
      lock.unlock();
      Status s = stop();
      lock.lock();
      if (!s.ok()) {
        // Leave the queue: the next ticket may go. A ticket not yet served is skipped over by
        // advancing past it once it reaches the head.
        if (serving_ == ticket) {
          ++serving_;
        } else {
          abandoned_.push_back(ticket);
        }
        skip_abandoned();
        changed_.notify_all();
        return s;
      }
    }
    changed_.wait_for(lock, std::chrono::milliseconds(50));
  }
  ++serving_;
  skip_abandoned();
  in_use_ += bytes;
  peak_ = std::max(peak_, in_use_);
  changed_.notify_all();
  return Reservation(this, bytes);
}

void MemoryBudget::skip_abandoned() {
  bool advanced = true;
  while (advanced) {
    advanced = false;
    const auto it = std::find(abandoned_.begin(), abandoned_.end(), serving_);
    if (it != abandoned_.end()) {
      abandoned_.erase(it);
      ++serving_;
      advanced = true;
    }
  }
}

void MemoryBudget::give_back(int64_t bytes) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    in_use_ -= bytes;
  }
  changed_.notify_all();
}

int64_t MemoryBudget::in_use() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return in_use_;
}

int64_t MemoryBudget::peak() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return peak_;
}

int64_t MemoryBudget::waiting() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return int64_t(next_ticket_ - serving_) - int64_t(abandoned_.size());
}

std::function<Status()> stop_when_held_too_long(std::function<Status()> stop, bool holding, int patience_ms,
                                                std::string why) {
  if (!holding) return stop;
  const auto since = std::chrono::steady_clock::now();
  return [stop = std::move(stop), since, patience_ms, why = std::move(why)]() -> Status {
    if (stop) SOIQ_RETURN_IF_ERROR(stop());
    if (std::chrono::steady_clock::now() - since > std::chrono::milliseconds(patience_ms))
      return resource_exhausted(why);
    return ok_status();
  };
}

}  // namespace soiq::server
