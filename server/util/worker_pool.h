#pragma once
// A fixed pool of worker threads for conversions and features (ServerConfig::workers bounds how
// many run at once, whatever the number of concurrent queries). Tasks run in submission order;
// the destructor finishes the queued tasks and joins.

#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <vector>

namespace soiq::server {

class WorkerPool {
 public:
  explicit WorkerPool(int threads) {
    for (int t = 0; t < threads; ++t) threads_.emplace_back([this] { run(); });
  }
  ~WorkerPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (auto& t : threads_) t.join();
  }
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  void submit(std::function<void()> task) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      queue_.push_back(std::move(task));
    }
    wake_.notify_one();
  }
  int size() const { return static_cast<int>(threads_.size()); }

  // Runs `work` on a worker and waits for what it returns: heavy work from every caller shares the
  // pool, so its size bounds how much runs at once. Never call it from a worker (it could wait for
  // itself).
  template <typename Work>
  std::invoke_result_t<Work&> call(Work& work) {
    // The promise is shared: the worker may still be inside set_value when get() returns.
    auto done = std::make_shared<std::promise<std::invoke_result_t<Work&>>>();
    auto result = done->get_future();
    submit([done, &work] { done->set_value(work()); });
    return result.get();  // `work` is only used before set_value, while this call waits
  }

 private:
  void run() {
    for (;;) {
      std::function<void()> task;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
        if (queue_.empty()) return;
        task = std::move(queue_.front());
        queue_.pop_front();
      }
      task();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
  bool stopping_ = false;
  std::vector<std::thread> threads_;
};

}  // namespace soiq::server
