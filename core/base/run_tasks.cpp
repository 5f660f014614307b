#include "core/base/run_tasks.h"

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
  int caller_cpu = -1;     // where the caller runs (works) when it queued the batch
  std::atomic<int64_t> next{0};
  std::atomic<int64_t> done{0};
};

#if defined(__linux__)
// Keeps the calling thread on one CPU while it lives, then gives back its own CPU set.
class CallerOnItsCpu {
 public:
  explicit CallerOnItsCpu(int cpu) {
    CPU_ZERO(&saved_);
    if (cpu < 0 || pthread_getaffinity_np(pthread_self(), sizeof saved_, &saved_) != 0 || !CPU_ISSET(cpu, &saved_) ||
        CPU_COUNT(&saved_) < 2)
      return;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    pinned_ = pthread_setaffinity_np(pthread_self(), sizeof one, &one) == 0;
  }
  ~CallerOnItsCpu() {
    if (pinned_) static_cast<void>(pthread_setaffinity_np(pthread_self(), sizeof saved_, &saved_));
  }
  CallerOnItsCpu(const CallerOnItsCpu&) = delete;
  CallerOnItsCpu& operator=(const CallerOnItsCpu&) = delete;

 private:
  cpu_set_t saved_;
  bool pinned_ = false;
};
#endif

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
#if defined(__linux__)
    batch->caller_cpu = sched_getcpu();
#endif
    {
      std::lock_guard<std::mutex> lock(mutex_);
      grow(batch->helpers_wanted);  // before the caller is held to one CPU: workers inherit its set
      queue_.push_back(batch);
      queued_.store(int(queue_.size()), std::memory_order_release);
    }
#if defined(__linux__)
    // The caller stays on its CPU for the batch and helpers keep off it: otherwise the scheduler
    // at times moved the caller onto the helper's CPU and kept it there, and a whole process ran
    // its 2-thread conversions at 1-thread speed.
    CallerOnItsCpu stay(batch->caller_cpu);
#endif
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
    while (int(workers_) < wanted) {
      std::thread([this] { worker(); }).detach();
      ++workers_;
    }
  }

#if defined(__linux__)
  // Keeps a helper off the CPU its batch's caller runs on (within the CPUs it may use at all):
  // left to the scheduler, a woken helper sometimes stayed on the caller's core for a whole
  // millisecond step, and 2 threads ran slower than 1 (seen in soiq-bench table5). Pinning helpers
  // to fixed CPUs instead made an unpinned caller collide with them. `excluded`: the CPU left out
  // of this helper's mask now, -1 for none; the mask changes only when that changes.
  static void avoid_cpu(const cpu_set_t& base, int cpu, int& excluded) {
    cpu_set_t set = base;
    if (cpu >= 0 && CPU_ISSET(cpu, &set) && CPU_COUNT(&set) > 1)
      CPU_CLR(cpu, &set);
    else
      cpu = -1;
    if (cpu == excluded) return;
    static_cast<void>(pthread_setaffinity_np(pthread_self(), sizeof set, &set));
    excluded = cpu;
  }
#endif

  void worker() {
#if defined(__linux__)
    cpu_set_t base;  // the CPUs this helper may use, as inherited from the thread that made it
    CPU_ZERO(&base);
    const bool have_base = pthread_getaffinity_np(pthread_self(), sizeof base, &base) == 0;
    int excluded = -1;
#endif
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
#if defined(__linux__)
      if (have_base) avoid_cpu(base, b->caller_cpu, excluded);
#endif
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
