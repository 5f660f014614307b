// The decoded-object cache: a key loads once however many threads ask at once, the byte budget
// holds, an error is not kept, and a cache that keeps on second use is not filled by a single pass.
#include "server/util/lru_cache.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

namespace soiq::server {
namespace {

int64_t size_of(const std::string& s) { return int64_t(s.size()); }

TEST(LruCache, AKeyAskedByManyThreadsAtOnceIsLoadedOnce) {
  LruCache<std::string> cache(1 << 20);
  std::atomic<int> loads{0};
  std::vector<std::thread> threads;
  std::vector<std::string> got(8);
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&, t] {
      auto r = cache.get_or_load(
          "image",
          [&]() -> Result<std::string> {
            ++loads;
            // Long enough that every other thread arrives while this load is in flight.
            std::this_thread::sleep_for(std::chrono::milliseconds(200));
            return std::string("decoded");
          },
          size_of);
      got[size_t(t)] = r.ok() ? **r : r.status().message();
    });
  }
  for (std::thread& t : threads) t.join();
  EXPECT_EQ(loads.load(), 1);
  for (const std::string& g : got) EXPECT_EQ(g, "decoded");
}

TEST(LruCache, AFailedLoadIsNotKeptAndIsTriedAgain) {
  LruCache<std::string> cache(1 << 20);
  int loads = 0;
  auto failing = [&]() -> Result<std::string> {
    ++loads;
    return Status(StatusCode::kDataLoss, "corrupt blob");
  };
  EXPECT_EQ(cache.get_or_load("k", failing, size_of).status().code(), StatusCode::kDataLoss);
  EXPECT_EQ(cache.get_or_load("k", failing, size_of).status().code(), StatusCode::kDataLoss);
  EXPECT_EQ(loads, 2);  // errors are not kept
}

TEST(LruCache, TheLeastRecentlyUsedGoFirstAndTheBudgetHolds) {
  LruCache<std::string> cache(10);
  int loads = 0;
  auto load = [&](const std::string& v) {
    return [&, v]() -> Result<std::string> {
      ++loads;
      return v;
    };
  };
  ASSERT_TRUE(cache.get_or_load("a", load("aaaa"), size_of).ok());
  ASSERT_TRUE(cache.get_or_load("b", load("bbbb"), size_of).ok());
  ASSERT_TRUE(cache.get_or_load("a", load("aaaa"), size_of).ok());  // a is now the most recent
  ASSERT_TRUE(cache.get_or_load("c", load("cccc"), size_of).ok());  // 12 bytes > 10: b goes
  EXPECT_EQ(loads, 3);
  ASSERT_TRUE(cache.get_or_load("a", load("aaaa"), size_of).ok());
  EXPECT_EQ(loads, 3);
  ASSERT_TRUE(cache.get_or_load("b", load("bbbb"), size_of).ok());
  EXPECT_EQ(loads, 4);
  auto big = cache.get_or_load("big", load(std::string(11, 'x')), size_of);  // returned, not kept
  ASSERT_TRUE(big.ok());
  ASSERT_TRUE(cache.get_or_load("big", load(std::string(11, 'x')), size_of).ok());
  EXPECT_EQ(loads, 6);
}

TEST(LruCache, KeepingOnSecondUseLeavesObjectsUsedOnceOutAndKeepsThoseUsedAgain) {
  LruCache<std::string> cache(1 << 20, LruCache<std::string>::Keep::kOnSecondUse);
  int loads = 0;
  auto load = [&]() -> Result<std::string> {
    ++loads;
    return std::string("mesh");
  };
  // A pass over many keys, each once: none is kept, so the second pass loads them all again...
  for (int pass = 0; pass < 2; ++pass) {
    for (int k = 0; k < 100; ++k) ASSERT_TRUE(cache.get_or_load("s" + std::to_string(k), load, size_of).ok());
  }
  EXPECT_EQ(loads, 200);
  // ...and keeps them: a third pass loads none.
  for (int k = 0; k < 100; ++k) ASSERT_TRUE(cache.get_or_load("s" + std::to_string(k), load, size_of).ok());
  EXPECT_EQ(loads, 200);
}

TEST(LruCache, KeysRememberedForASecondUseAreBounded) {
  using Cache = LruCache<std::string>;
  Cache cache(1 << 20, Cache::Keep::kOnSecondUse);
  int loads = 0;
  auto load = [&]() -> Result<std::string> {
    ++loads;
    return std::string("m");
  };
  ASSERT_TRUE(cache.get_or_load("first", load, size_of).ok());
  // As many other keys as the cache remembers push "first" out of its memory...
  for (size_t k = 0; k < Cache::kSeenKeys; ++k) ASSERT_TRUE(cache.get_or_load(std::to_string(k), load, size_of).ok());
  // ...so its next use counts as a first use again: loaded, not kept; the one after that is kept.
  ASSERT_TRUE(cache.get_or_load("first", load, size_of).ok());
  ASSERT_TRUE(cache.get_or_load("first", load, size_of).ok());
  ASSERT_TRUE(cache.get_or_load("first", load, size_of).ok());
  EXPECT_EQ(loads, int(Cache::kSeenKeys) + 3);
}

}  // namespace
}  // namespace soiq::server
