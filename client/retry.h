#pragma once
// Retries of a call that failed with UNAVAILABLE (soiqd restarting, a dropped connection), with
// exponential backoff. Only for calls that are safe to repeat: gets, lists, info, convert,
// features, a query before any row arrived, and uploads (the data is local and resent whole).
//
// Inputs: a policy (attempts >= 1; the first wait, the factor between waits and the longest
// wait), a call that returns a soiq::Status and is repeated from scratch, and the sleep (real time
// by default; tests pass their own). Output: the first non-UNAVAILABLE status, or the last
// UNAVAILABLE after `attempts` tries. `retryable` may veto a retry (e.g. a row was already
// delivered). Thread-safe when the call is.

#include <chrono>
#include <functional>
#include <vector>

#include "core/base/status.h"

namespace soiq::client {

struct RetryPolicy {
  int attempts = 3;  // tries in all; 1 = no retry
  std::chrono::milliseconds initial_backoff{100};
  double multiplier = 4;  // 100 ms, then 400 ms
  std::chrono::milliseconds max_backoff{2000};
};

// The waits between the tries of `policy`: attempts - 1 of them.
std::vector<std::chrono::milliseconds> backoff_delays(const RetryPolicy& policy);

using SleepFn = std::function<void(std::chrono::milliseconds)>;

Status with_retries(const RetryPolicy& policy, const std::function<Status()>& call,
                    const std::function<bool()>& retryable = {}, const SleepFn& sleep = {});

}  // namespace soiq::client
