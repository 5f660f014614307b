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
