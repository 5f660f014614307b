#include "server/app/memory_budget.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>
#include <vector>

namespace soiq::server {
namespace {

TEST(MemoryBudget, ARequestOverTheWholeBudgetIsRefusedAtOnce) {
  MemoryBudget budget(1000);
  auto r = budget.reserve(1001, "structure 7");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kResourceExhausted);
  EXPECT_NE(r.status().message().find("structure 7 needs an estimated 1.00 KB"), std::string::npos)
      << r.status().message();
  EXPECT_NE(r.status().message().find("memory budget of 1.00 KB"), std::string::npos) << r.status().message();
  EXPECT_EQ(budget.in_use(), 0);
}

// soiqd's caches of decoded surfaces and images are inside its budget: their share is set aside,
// and work is admitted against what is left, so caching and working together stay under the limit.
TEST(MemoryBudget, TheCachesShareIsSetAsideAndWorkIsAdmittedAgainstTheRest) {
  EXPECT_EQ(decoded_cache_share(int64_t(256) << 20), int64_t(64) << 20);
  EXPECT_EQ(decoded_cache_share(int64_t(64) << 30), int64_t(2) << 30);  // at most 2 GiB
  EXPECT_EQ(decoded_cache_share(0), 0);

  MemoryBudget budget(1000, 250);
  EXPECT_EQ(budget.limit(), 1000);
  EXPECT_EQ(budget.cache_bytes(), 250);
  EXPECT_EQ(budget.work_limit(), 750);
  auto too_big = budget.reserve(751, "structure 7");
  ASSERT_FALSE(too_big.ok());
  EXPECT_EQ(too_big.status().code(), StatusCode::kResourceExhausted);
  EXPECT_NE(too_big.status().message().find(
                "more than the 750 bytes that soiqd's memory budget of 1.00 KB leaves beside 250 bytes of "
                "decoded-object caches"),
            std::string::npos)
      << too_big.status().message();

  auto fits = budget.reserve(750, "a");
  ASSERT_TRUE(fits.ok());
  std::atomic<bool> waited_out{false};
  // With the work share full, one more byte waits (and here gives up), although the limit is 1000.
  auto more = budget.reserve(1, "b", [&] {
    waited_out = true;
    return Status(StatusCode::kCancelled, "stop");
  });
  EXPECT_FALSE(more.ok());
  EXPECT_TRUE(waited_out);
  EXPECT_EQ(budget.in_use(), 750);

  EXPECT_EQ(MemoryBudget(100, 500).cache_bytes(), 100);  // never more than the whole
}

// A reservation asked while others are held (the next SEG of a study) waits only so long, then gives
// up naming why: otherwise two such callers could each wait for the other's bytes forever.
TEST(MemoryBudget, AWaitWhileHoldingGivesUpAfterItsPatienceAndOneNotHoldingWaitsOn) {
  MemoryBudget budget(1000);
  auto first = budget.reserve(800, "first SEG");
  ASSERT_TRUE(first.ok());
  const auto start = std::chrono::steady_clock::now();
  auto second = budget.reserve(
      400, "second SEG", stop_when_held_too_long({}, /*holding=*/true, 200, "the study's SEGs do not fit at once"));
  const auto waited = std::chrono::steady_clock::now() - start;
  ASSERT_FALSE(second.ok());
  EXPECT_EQ(second.status().code(), StatusCode::kResourceExhausted);
  EXPECT_EQ(second.status().message(), "the study's SEGs do not fit at once");
  EXPECT_GE(waited, std::chrono::milliseconds(200));  // it did wait its patience first
  EXPECT_EQ(budget.in_use(), 800);
  EXPECT_EQ(budget.waiting(), 0);

  // Not holding anything, the caller's own stop alone decides: here it never stops, and the wait
  // ends when the bytes come back.
  const std::function<Status()> never = [] { return ok_status(); };
  const std::function<Status()> same = stop_when_held_too_long(never, /*holding=*/false, 1, "unused");
  std::thread release([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    first = Result<MemoryBudget::Reservation>(internal_error("released"));
  });
  auto third = budget.reserve(400, "third", same);
  release.join();
  ASSERT_TRUE(third.ok()) << third.status().to_string();
  EXPECT_EQ(budget.in_use(), 400);

  // The caller's own stop still ends a wait while holding, before the patience.
  auto fourth = budget.reserve(
      700, "fourth",
      stop_when_held_too_long([] { return Status(StatusCode::kCancelled, "gone"); }, true, 60000, "unused"));
  ASSERT_FALSE(fourth.ok());
  EXPECT_EQ(fourth.status().code(), StatusCode::kCancelled);
}

TEST(MemoryBudget, ReservationsAddUpAndGoBackWhenReleased) {
  MemoryBudget budget(1000);
  {
    auto a = budget.reserve(600, "a");
    ASSERT_TRUE(a.ok());
    auto b = budget.reserve(400, "b");
    ASSERT_TRUE(b.ok());
    EXPECT_EQ(budget.in_use(), 1000);
    MemoryBudget::Reservation moved = std::move(*b);
    EXPECT_EQ(budget.in_use(), 1000);
  }
  EXPECT_EQ(budget.in_use(), 0);
  EXPECT_EQ(budget.peak(), 1000);
}

// A large request waiting for room is not overtaken by small ones that would fit: otherwise a
// stream of small conversions could starve a large one forever.
// Blocks until `n` reservations wait in `budget` (the threads have taken their tickets).
void wait_for_waiters(const MemoryBudget& budget, int64_t n) {
  while (budget.waiting() < n) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

TEST(MemoryBudget, WaitersAreServedFirstComeFirstServed) {
  MemoryBudget budget(100);
  auto held = budget.reserve(80, "held");
  ASSERT_TRUE(held.ok());
  std::mutex m;
  std::vector<char> order;
  // "big" and "small" never fit together, so the one served first records first.
  std::thread big([&] {
    auto r = budget.reserve(95, "big");
    ASSERT_TRUE(r.ok());
    std::lock_guard<std::mutex> lock(m);
    order.push_back('B');
  });
  wait_for_waiters(budget, 1);  // "big" has its ticket
  std::thread small([&] {
    auto r = budget.reserve(10, "small");  // fits beside "held", but "big" came first
    ASSERT_TRUE(r.ok());
    std::lock_guard<std::mutex> lock(m);
    order.push_back('s');
  });
  wait_for_waiters(budget, 2);
  std::this_thread::sleep_for(std::chrono::milliseconds(100));  // room for a wrong admission to show
  {
    std::lock_guard<std::mutex> lock(m);
    EXPECT_TRUE(order.empty());
  }
  EXPECT_EQ(budget.waiting(), 2);
  *held = MemoryBudget::Reservation();  // release
  big.join();
  small.join();
  ASSERT_EQ(order.size(), 2u);
  EXPECT_EQ(order[0], 'B');
  EXPECT_EQ(budget.in_use(), 0);
  EXPECT_EQ(budget.waiting(), 0);
}

TEST(MemoryBudget, AStoppedWaiterLeavesTheQueueAndTheNextOneProceeds) {
  MemoryBudget budget(100);
  auto held = budget.reserve(100, "held");
  ASSERT_TRUE(held.ok());
  std::atomic<bool> cancel{false};
  Status waited;
  std::thread waiter([&] {
    auto r = budget.reserve(60, "waiter", [&]() -> Status {
      return cancel ? Status(StatusCode::kCancelled, "cancelled by the client") : ok_status();
    });
    waited = r.ok() ? ok_status() : r.status();
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  cancel = true;
  waiter.join();
  EXPECT_EQ(waited.code(), StatusCode::kCancelled);
  *held = MemoryBudget::Reservation();
  auto next = budget.reserve(100, "next");  // would block forever if the cancelled ticket stayed
  EXPECT_TRUE(next.ok());
}

}  // namespace
}  // namespace soiq::server
