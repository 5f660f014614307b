#pragma once
// Cancels a gRPC call when a caller's flag becomes true, even while the call is blocked in Read():
// a thread polls the flag every 50 ms and calls ClientContext::TryCancel (thread-safe). Stops when
// destroyed. With a null flag it does nothing and starts no thread. Internal to the client.

#include <grpcpp/client_context.h>

#include <atomic>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace soiq::client {

class CancelWatcher {
 public:
  CancelWatcher(const std::atomic<bool>* flag, grpc::ClientContext* context);
  ~CancelWatcher();
  CancelWatcher(const CancelWatcher&) = delete;
  CancelWatcher& operator=(const CancelWatcher&) = delete;

  // True once the flag was seen set (the call was cancelled on the caller's behalf).
  bool fired() const { return fired_.load(); }

 private:
  std::atomic<bool> fired_{false};
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace soiq::client
