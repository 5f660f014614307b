#pragma once
// A thread-safe least-recently-used cache of immutable decoded objects (surfaces, images) with a
// byte budget: decoding a stored blob costs milliseconds, and a query touches the same study image
// for every structure of the study.
//
// get_or_load(key, load) returns the cached object or calls `load` (outside the lock; two threads
// missing the same key may both load, the first to finish is kept) and caches a success. Objects
// larger than the whole budget are returned but not kept.

#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/base/status.h"

namespace soiq::server {

template <typename T>
class LruCache {
 public:
  using Ptr = std::shared_ptr<const T>;
  explicit LruCache(int64_t budget_bytes) : budget_(budget_bytes) {}

  Result<Ptr> get_or_load(const std::string& key, const std::function<Result<T>()>& load,
                          const std::function<int64_t(const T&)>& bytes_of) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = index_.find(key);
      if (it != index_.end()) {
        order_.splice(order_.begin(), order_, it->second);
        return it->second->value;
      }
    }
    SOIQ_ASSIGN_OR_RETURN(T loaded, load());
    const int64_t bytes = bytes_of(loaded);
    Ptr value = std::make_shared<const T>(std::move(loaded));
    if (bytes > budget_) return value;
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = index_.find(key);
    if (it != index_.end()) return it->second->value;
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

 private:
  struct Entry {
    std::string key;
    Ptr value;
    int64_t bytes;
  };
  const int64_t budget_;
  std::mutex mutex_;
  std::list<Entry> order_;  // most recent first
  std::unordered_map<std::string, typename std::list<Entry>::iterator> index_;
  int64_t used_ = 0;
};

}  // namespace soiq::server
