#pragma once
// A thread-safe least-recently-used cache of immutable decoded objects (surfaces, images) with a
// byte budget: decoding a stored blob costs milliseconds, and a query touches the same study image
// for every structure of the study.
//
// get_or_load(key, load) returns the cached object or calls `load` (outside the lock) and caches a
// success. A key is loaded once at a time: a thread that misses a key another is loading waits for
// that load and shares its result (or its error), so a study's image is decoded once however many
// workers ask for it at the same moment. Objects larger than the whole budget are returned but not
// kept.
//
// Keep::kOnSecondUse keeps an object only when its key was loaded before (the cache remembers the
// last kSeenKeys keys it loaded, not their objects): a pass over many objects each used once (a
// cold query's stage 2 decodes every candidate's surface once) then neither grows the cache nor
// evicts what is used again, and the decoded bytes go back to the allocator for the next decode.
// Measured on soiq-bench query's cold query: a cache growing by ~1.3 GB of first-use surfaces
// made soiqd spend a fifth of its time on page faults of fresh memory.

#include <cstdint>
#include <deque>
#include <functional>
#include <future>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "core/base/status.h"

namespace soiq::server {

template <typename T>
class LruCache {
 public:
  using Ptr = std::shared_ptr<const T>;
  enum class Keep { kOnFirstUse, kOnSecondUse };
  // Keys remembered for kOnSecondUse: ~100 bytes each, ~1.6 MB in all.
  static constexpr size_t kSeenKeys = 16384;

  explicit LruCache(int64_t budget_bytes, Keep keep = Keep::kOnFirstUse) : budget_(budget_bytes), keep_(keep) {}

  Result<Ptr> get_or_load(const std::string& key, const std::function<Result<T>()>& load,
                          const std::function<int64_t(const T&)>& bytes_of) {
    std::unique_lock<std::mutex> lock(mutex_);
    auto it = index_.find(key);
    if (it != index_.end()) {
      order_.splice(order_.begin(), order_, it->second);
      return it->second->value;
    }
    auto in_flight = loading_.find(key);
    if (in_flight != loading_.end()) {
      const std::shared_future<Result<Ptr>> theirs = in_flight->second;
      lock.unlock();  // the loader needs the lock to publish
      return theirs.get();
    }
    std::promise<Result<Ptr>> mine;
    loading_.emplace(key, mine.get_future().share());
    lock.unlock();
    try {
      Result<Ptr> result = load_value(load, bytes_of, key);
      mine.set_value(result);
      lock.lock();
      loading_.erase(key);
      return result;
    } catch (...) {  // out of memory while decoding: the waiters get it too, none waits forever
      mine.set_exception(std::current_exception());
      lock.lock();
      loading_.erase(key);
      throw;
    }
  }

 private:
  struct Entry {
    std::string key;
    Ptr value;
    int64_t bytes;
  };

  // Loads `key` and keeps it when it fits; called by the one thread that loads it.
  Result<Ptr> load_value(const std::function<Result<T>()>& load, const std::function<int64_t(const T&)>& bytes_of,
                         const std::string& key) {
    Result<T> loaded = load();
    if (!loaded.ok()) return loaded.status();
    const int64_t bytes = bytes_of(*loaded);
    Ptr value = std::make_shared<const T>(std::move(loaded).value());
    if (bytes > budget_) return value;
    std::lock_guard<std::mutex> lock(mutex_);
    if (keep_ == Keep::kOnSecondUse && !seen_before(key)) return value;
    order_.push_front(Entry{key, value, bytes});
    index_[key] = order_.begin();
    used_ += bytes;
    while (used_ > budget_ && !order_.empty()) {
      used_ -= order_.back().bytes;
      index_.erase(order_.back().key);
      order_.pop_back();
    }
    return value;
  }

  // Whether `key` was loaded before; remembers it for next time. Called under the lock.
  bool seen_before(const std::string& key) {
    if (seen_.count(key) != 0) return true;
    if (seen_order_.size() == kSeenKeys) {
      seen_.erase(seen_order_.front());
      seen_order_.pop_front();
    }
    seen_.insert(key);
    seen_order_.push_back(key);
    return false;
  }

  const int64_t budget_;
  const Keep keep_;
  std::mutex mutex_;
  std::list<Entry> order_;  // most recent first
  std::unordered_map<std::string, typename std::list<Entry>::iterator> index_;
  int64_t used_ = 0;
  std::unordered_map<std::string, std::shared_future<Result<Ptr>>> loading_;  // keys being loaded now
  std::unordered_set<std::string> seen_;  // kOnSecondUse: keys loaded before, oldest first below
  std::deque<std::string> seen_order_;
};

}  // namespace soiq::server
