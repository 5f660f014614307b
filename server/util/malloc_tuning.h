#pragma once
// glibc's allocator tuned for soiqd's work: every cold structure allocates and frees a few large
// blocks (a decoded surface is ~2.4 MB per 100k triangles, then the conversion's and the features'
// buffers). By default glibc serves blocks above its (adaptive) mmap threshold with fresh mappings
// and returns freed memory at the top of a heap to the kernel beyond 128 KiB, so the next structure
// page-faults its buffers in again: measured, a fresh 2.4 MB mesh costs 0.72 ms to allocate and
// zero, a reused one 0.04 ms; the cold 1,000-structure query of soiq-bench took 1.49 s, 1.25 s with
// blocks up to 8 MiB kept in the heaps and 16 MiB of free memory kept per heap.
//
// The cost: each malloc arena (glibc makes up to 8 per core) may keep up to 16 MiB of freed
// memory mapped. That memory is reused, not leaked, and is outside the memory budget
// (server/app/memory_budget.h), which counts the bytes in use.
//
// Call once, first thing in main(), before any thread starts. Returns whether glibc took both
// settings; false (and nothing done) elsewhere than glibc.

namespace soiq::server {

bool keep_freed_blocks_for_reuse();

}  // namespace soiq::server
