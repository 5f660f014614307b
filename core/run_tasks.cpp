#include "core/run_tasks.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>

namespace soiq {
namespace {

struct Batch {
  const std::function<void(int64_t)>* task = nullptr;  // valid while the caller waits in run_tasks
  int64_t count = 0;
  int helpers_wanted = 0;
  int helpers_joined = 0;  // under Pool::mutex_
  std::atomic<int64_t> next{0};
  std::atomic<int64_t> done{0};
};

class Pool {
 public:
  // Never destroyed: workers sleep until the process exits (no join at static destruction).
  static Pool& instance() {
    static Pool* pool = new Pool();
    return *pool;
  }

  void run(int64_t count, int threads, const std::function<void(int64_t)>& task) {
    auto batch = std::make_shared<Batch>();
    batch->task = &task;
    batch->count = count;
    batch->helpers_wanted = int(std::min<int64_t>(threads - 1, count - 1));
    {
      std::lock_guard<std::mutex> lock(mutex_);
      grow(batch->helpers_wanted);
      queue_.push_back(batch);
    }
    if (batch->helpers_wanted == 1)
      work_cv_.notify_one();
    else
      work_cv_.notify_all();
    work_on(*batch);
    std::unique_lock<std::mutex> lock(mutex_);
    // Helpers that never came must not find it later; those that came hold their own reference.
    queue_.erase(std::remove(queue_.begin(), queue_.end(), batch), queue_.end());
    done_cv_.wait(lock, [&] { return batch->done.load() == batch->count; });
  }

 private:
  Pool() = default;

  // Takes tasks until none is left. The task is only touched after a valid index was taken,
  // while the caller still waits for it to be done.
  void work_on(Batch& b) {
    for (int64_t i; (i = b.next.fetch_add(1)) < b.count;) {
      (*b.task)(i);
      if (b.done.fetch_add(1) + 1 == b.count) {
        std::lock_guard<std::mutex> lock(mutex_);
        done_cv_.notify_all();
      }
    }
  }

  void grow(int helpers) {  // under mutex_
    const int wanted = std::clamp(std::max<int>(helpers, int(std::thread::hardware_concurrency()) - 1), 1, 255);
    while (int(workers_) < wanted) {
      std::thread([this] { worker(); }).detach();
      ++workers_;
    }
  }

  void worker() {
    for (;;) {
      std::shared_ptr<Batch> b;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        work_cv_.wait(lock, [&] { return !queue_.empty(); });
        b = queue_.front();
        if (++b->helpers_joined >= b->helpers_wanted) queue_.pop_front();
      }
      work_on(*b);
    }
  }

  std::mutex mutex_;
  std::condition_variable work_cv_;  // a batch was queued
  std::condition_variable done_cv_;  // a batch's last task finished
  std::deque<std::shared_ptr<Batch>> queue_;
  int workers_ = 0;
};

}  // namespace

void run_tasks(int64_t count, int threads, const std::function<void(int64_t)>& task) {
  if (count <= 0) return;
  if (threads <= 1 || count == 1) {
    for (int64_t i = 0; i < count; ++i) task(i);
    return;
  }
  Pool::instance().run(count, threads, task);
}

}  // namespace soiq
