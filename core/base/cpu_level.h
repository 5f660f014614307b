#pragma once
// Which instruction set soiq's hot kernels run with (cpu_dispatch.h): the x86-64 micro-architecture
// levels of the psABI. One portable build (no -march) carries each kernel three times and picks at
// run time, so `make run` is as fast as a build tuned for the machine, and the same binary still
// runs on any x86-64.
//
//   kBaseline  x86-64: SSE2 (every x86-64 CPU)
//   kV2        x86-64-v2: + SSE3, SSSE3, SSE4.1, SSE4.2, POPCNT, CMPXCHG16B (SSE4.1's roundsd is
//              floor, ceil and nearbyint in one instruction: the scanline's lattice ranges)
//   kV3        x86-64-v3: + AVX, AVX2, BMI1, BMI2, F16C, FMA, LZCNT, MOVBE, with the OS saving the
//              AVX state (XGETBV)
//
// Outputs do not depend on the level: core builds with -ffp-contract=off, so no level fuses a
// multiply and an add, and every level rounds each operation alike (tests/core/cpu_level_test.cpp
// converts, measures and decodes at each level and compares bit for bit).
//
// Thread-safety: detected_cpu_level() probes once (thread-safe static); cpu_level() is a relaxed
// atomic read; cap_cpu_level() is for tests and benchmarks, before or between runs.

#include <optional>
#include <string_view>

namespace soiq {

enum class CpuLevel { kBaseline = 1, kV2 = 2, kV3 = 3 };

// The highest level this CPU and its OS run (cpuid, and xgetbv for the AVX state); kBaseline on
// anything that is not x86-64.
CpuLevel detected_cpu_level();

// The level dispatched kernels use: detected_cpu_level(), or less if capped.
CpuLevel cpu_level();

// Caps cpu_level() at `cap` (a cap above the detected level changes nothing); nullopt removes it.
void cap_cpu_level(std::optional<CpuLevel> cap);

// "x86-64", "x86-64-v2", "x86-64-v3": the names -march takes.
std::string_view cpu_level_name(CpuLevel level);

// The level of a name cpu_level_name gives; nullopt for anything else.
std::optional<CpuLevel> parse_cpu_level(std::string_view name);

}  // namespace soiq
