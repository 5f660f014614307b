#include "client/cancel_watcher.h"

#include <chrono>

namespace soiq::client {

CancelWatcher::CancelWatcher(const std::atomic<bool>* flag, grpc::ClientContext* context) {
  if (flag == nullptr) return;
  thread_ = std::thread([this, flag, context] {
    std::unique_lock lock(mutex_);
    while (!stop_) {
      if (flag->load()) {
        fired_ = true;
        context->TryCancel();
        return;
      }
      wake_.wait_for(lock, std::chrono::milliseconds(50));
    }
  });
}

CancelWatcher::~CancelWatcher() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

}  // namespace soiq::client
