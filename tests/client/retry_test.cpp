#include "client/retry.h"

#include <gtest/gtest.h>

namespace soiq::client {
namespace {

TEST(BackoffDelays, GrowByTheMultiplierUpToTheCap) {
  RetryPolicy p;
  p.attempts = 5;
  p.initial_backoff = std::chrono::milliseconds(100);
  p.multiplier = 4;
  p.max_backoff = std::chrono::milliseconds(2000);
  const auto d = backoff_delays(p);
  ASSERT_EQ(d.size(), 4u);
  EXPECT_EQ(d[0].count(), 100);
  EXPECT_EQ(d[1].count(), 400);
  EXPECT_EQ(d[2].count(), 1600);
  EXPECT_EQ(d[3].count(), 2000);
}

TEST(WithRetries, RepeatsUnavailableThenSucceeds) {
  int calls = 0;
  std::vector<long long> slept;
  const Status s = with_retries(
      RetryPolicy{}, [&] { return ++calls < 3 ? Status(StatusCode::kUnavailable, "down") : ok_status(); }, {},
      [&](std::chrono::milliseconds ms) { slept.push_back(ms.count()); });
  EXPECT_TRUE(s.ok());
  EXPECT_EQ(calls, 3);
  EXPECT_EQ(slept, (std::vector<long long>{100, 400}));
}

TEST(WithRetries, GivesUpAfterTheLastAttemptWithTheLastStatus) {
  int calls = 0;
  const Status s = with_retries(
      RetryPolicy{}, [&] { return Status(StatusCode::kUnavailable, "try " + std::to_string(++calls)); }, {},
      [](std::chrono::milliseconds) {});
  EXPECT_EQ(s.code(), StatusCode::kUnavailable);
  EXPECT_EQ(s.message(), "try 3");
}

TEST(WithRetries, OtherErrorsAreNotRetried) {
  int calls = 0;
  const Status s = with_retries(
      RetryPolicy{}, [&] { return ++calls, not_found("no structure 4"); }, {}, [](std::chrono::milliseconds) {});
  EXPECT_EQ(s.code(), StatusCode::kNotFound);
  EXPECT_EQ(calls, 1);
}

TEST(WithRetries, VetoStopsTheRetry) {
  int calls = 0;
  const Status s = with_retries(
      RetryPolicy{}, [&] { return ++calls, Status(StatusCode::kUnavailable, "down"); }, [] { return false; },
      [](std::chrono::milliseconds) {});
  EXPECT_EQ(s.code(), StatusCode::kUnavailable);
  EXPECT_EQ(calls, 1);
}

}  // namespace
}  // namespace soiq::client
