#include "core/run_tasks.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#if defined(__linux__)
#include <pthread.h>
#include <sched.h>
#endif

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
      queued_.store(int(queue_.size()), std::memory_order_release);
    }
    if (batch->helpers_wanted == 1)
      work_cv_.notify_one();
    else
      work_cv_.notify_all();
    work_on(*batch);
    std::unique_lock<std::mutex> lock(mutex_);
    // Helpers that never came must not find it later; those that came hold their own reference.
    queue_.erase(std::remove(queue_.begin(), queue_.end(), batch), queue_.end());
    queued_.store(int(queue_.size()), std::memory_order_release);
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
    const std::vector<int> cpus = allowed_cpus();
    while (int(workers_) < wanted) {
      // Worker w keeps to the (w+1)-th CPU the creating thread may use, so the caller (who always
      // works too) and its helpers start on different cores: left to the scheduler, a woken helper
      // often stayed on the caller's core for the whole of a millisecond step (table5 measured a
      // 2-thread conversion slower than 1 thread).
      const int cpu = cpus.empty() ? -1 : cpus[size_t(workers_ + 1) % cpus.size()];
      std::thread([this, cpu] {
        keep_to_cpu(cpu);
        worker();
      }).detach();
      ++workers_;
    }
  }

  // The CPUs the calling thread may run on, in order; empty where that cannot be asked.
  static std::vector<int> allowed_cpus() {
    std::vector<int> out;
#if defined(__linux__)
    cpu_set_t set;
    CPU_ZERO(&set);
    if (pthread_getaffinity_np(pthread_self(), sizeof set, &set) == 0)
      for (int c = 0; c < CPU_SETSIZE; ++c)
        if (CPU_ISSET(c, &set)) out.push_back(c);
#endif
    return out;
  }

  static void keep_to_cpu(int cpu) {
#if defined(__linux__)
    if (cpu < 0) return;
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    static_cast<void>(pthread_setaffinity_np(pthread_self(), sizeof set, &set));
#else
    static_cast<void>(cpu);
#endif
  }

  void worker() {
    for (;;) {
      // Spin a little before sleeping: the parallel steps of one conversion come tens of
      // microseconds apart, and waking a sleeping thread on a virtual machine takes about as long
      // as a step (measured: a 2-thread bucketing pass ran mostly on its caller).
      const auto spin_until = std::chrono::steady_clock::now() + std::chrono::microseconds(200);
      while (queued_.load(std::memory_order_acquire) == 0 && std::chrono::steady_clock::now() < spin_until) {
#if defined(__x86_64__)
        __builtin_ia32_pause();
#endif
      }
      std::shared_ptr<Batch> b;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        work_cv_.wait(lock, [&] { return !queue_.empty(); });
        b = queue_.front();
        if (++b->helpers_joined >= b->helpers_wanted) queue_.pop_front();
        queued_.store(int(queue_.size()), std::memory_order_release);
      }
      work_on(*b);
    }
  }

  std::mutex mutex_;
  std::condition_variable work_cv_;  // a batch was queued
  std::condition_variable done_cv_;  // a batch's last task finished
  std::deque<std::shared_ptr<Batch>> queue_;
  std::atomic<int> queued_{0};  // queue_.size(), readable without the mutex (workers spin on it)
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
