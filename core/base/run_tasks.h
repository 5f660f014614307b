#pragma once
// Runs task(0), ..., task(count - 1), each exactly once, on the calling thread and up to
// `threads - 1` workers of a process-wide pool, and returns when all have finished. The parallel
// steps of core/ (parallel_for.h, the 1D method's slabs) go through it, so a step costs a wake-up
// of sleeping workers (microseconds) instead of creating threads: on our 2-vCPU machines a
// std::thread create + join took ~0.1 ms, and the five of a 2-thread SM1 conversion were a fifth
// of its time.
//
// Inputs   count >= 0 tasks; threads: how many threads may work at once (<= 1: all on the caller).
//          task: must not throw; tasks are taken in index order, each by whichever thread is free,
//          so results must not depend on which thread ran which task (write to task-indexed slots).
// Output   none; every task has run when run_tasks returns.
// Cost     the tasks, plus one mutex round trip and a condition-variable wake per helper.
// Threads  safe to call from several threads at once and from inside a task: the caller always
//          takes tasks itself, so a busy pool only means less help, never a wait for a worker.
//          The pool starts on first use with hardware_concurrency() - 1 workers (at least one),
//          grows to the largest `threads - 1` asked (at most 255), and lives until the process ends.
//          Workers spin ~200 us for the next batch before sleeping (a conversion's steps come tens
//          of microseconds apart), and a worker joining a batch keeps off the CPU its caller is on,
//          within the CPUs the worker inherited (Linux).

#include <cstdint>
#include <functional>

namespace soiq {

void run_tasks(int64_t count, int threads, const std::function<void(int64_t)>& task);

}  // namespace soiq
