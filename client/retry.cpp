#include "client/retry.h"

#include <algorithm>
#include <thread>

namespace soiq::client {

std::vector<std::chrono::milliseconds> backoff_delays(const RetryPolicy& policy) {
  std::vector<std::chrono::milliseconds> delays;
  double ms = double(policy.initial_backoff.count());
  for (int i = 1; i < policy.attempts; ++i) {
    delays.emplace_back(std::min<long long>((long long)ms, policy.max_backoff.count()));
    ms *= policy.multiplier;
  }
  return delays;
}

Status with_retries(const RetryPolicy& policy, const std::function<Status()>& call,
                    const std::function<bool()>& retryable, const SleepFn& sleep) {
  const std::vector<std::chrono::milliseconds> delays = backoff_delays(policy);
  for (size_t attempt = 0;; ++attempt) {
    Status s = call();
    if (s.code() != StatusCode::kUnavailable || attempt >= delays.size()) return s;
    if (retryable && !retryable()) return s;
    if (sleep) {
      sleep(delays[attempt]);
    } else {
      std::this_thread::sleep_for(delays[attempt]);
    }
  }
}

}  // namespace soiq::client
