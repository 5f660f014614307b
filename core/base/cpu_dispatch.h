#pragma once
// cpu_dispatch(f): runs f() compiled for the best instruction set of cpu_level() (cpu_level.h).
//
// How: three instantiations of a one-line trampoline, each with GCC's and Clang's `target` (the
// level's ISA extensions) and `flatten` (inline every call inside it, recursively, where the callee
// is visible). f's body, and every function it calls that is defined in a header or in the same
// translation unit, is thereby compiled three times, once per level; calls the compiler cannot
// inline (another .cpp, libc, a std::function) go to their one ordinary copy, which is safe on any
// CPU. Nothing emits an out-of-line copy of a shared inline function for a higher level, so the
// linker can never pick an AVX2 copy for baseline code (the trap of compiling whole files with
// different -march flags).
//
// Use it around a kernel's hot loop where the loop's callees are visible: a thread task's body,
// not around run_tasks (which calls through std::function and would leave the tasks uninlined).
// The extra code is one copy of the kernel per level; the cost per call one relaxed atomic load.
//
// The feature lists spell out the psABI levels, rather than "arch=x86-64-v3", because Clang 14
// (the sanitizer build) does not take the level names there.

#include <utility>

#include "core/base/cpu_level.h"

namespace soiq {

namespace cpu_dispatch_detail {

#if defined(__x86_64__)
#define SOIQ_TARGET_V2 "sse3,ssse3,sse4.1,sse4.2,popcnt,cx16"
#define SOIQ_TARGET_V3 SOIQ_TARGET_V2 ",avx,avx2,bmi,bmi2,f16c,fma,lzcnt,movbe"

template <typename F>
[[gnu::target(SOIQ_TARGET_V3), gnu::flatten]] decltype(auto) run_v3(F& f) {
  return f();
}
template <typename F>
[[gnu::target(SOIQ_TARGET_V2), gnu::flatten]] decltype(auto) run_v2(F& f) {
  return f();
}

#undef SOIQ_TARGET_V3
#undef SOIQ_TARGET_V2
#endif

template <typename F>
[[gnu::flatten]] decltype(auto) run_baseline(F& f) {
  return f();
}

}  // namespace cpu_dispatch_detail

template <typename F>
decltype(auto) cpu_dispatch(F&& f) {
#if defined(__x86_64__)
  switch (cpu_level()) {
    case CpuLevel::kV3:
      return cpu_dispatch_detail::run_v3(f);
    case CpuLevel::kV2:
      return cpu_dispatch_detail::run_v2(f);
    case CpuLevel::kBaseline:
      break;
  }
#endif
  return cpu_dispatch_detail::run_baseline(f);
}

}  // namespace soiq
