#include "core/base/cpu_level.h"

#include <atomic>

#if defined(__x86_64__)
#include <cpuid.h>
#endif

namespace soiq {

namespace {

#if defined(__x86_64__)
struct CpuidBits {
  unsigned eax = 0, ebx = 0, ecx = 0, edx = 0;
};

CpuidBits cpuid(unsigned leaf, unsigned subleaf) {
  CpuidBits r;
  if (!__get_cpuid_count(leaf, subleaf, &r.eax, &r.ebx, &r.ecx, &r.edx)) return CpuidBits{};
  return r;
}

bool has(unsigned reg, int bit) { return (reg >> bit) & 1u; }

CpuLevel probe() {
  const CpuidBits l1 = cpuid(1, 0);
  const CpuidBits l7 = cpuid(7, 0);
  const CpuidBits e1 = cpuid(0x80000001u, 0);
  // Leaf 1 ECX: SSE3 0, SSSE3 9, FMA 12, CX16 13, SSE4.1 19, SSE4.2 20, MOVBE 22, POPCNT 23,
  // XSAVE 26, OSXSAVE 27, AVX 28, F16C 29. Extended leaf 1 ECX: LAHF 0, LZCNT 5.
  const bool v2 = has(l1.ecx, 0) && has(l1.ecx, 9) && has(l1.ecx, 13) && has(l1.ecx, 19) && has(l1.ecx, 20) &&
                  has(l1.ecx, 23) && has(e1.ecx, 0);
  if (!v2) return CpuLevel::kBaseline;
  // AVX needs the OS to save the YMM state: XCR0 bits 1 (SSE) and 2 (AVX), read only when OSXSAVE.
  bool os_avx = false;
  if (has(l1.ecx, 27)) {
    unsigned lo = 0, hi = 0;
    __asm__("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    os_avx = (lo & 6u) == 6u;
  }
  // Leaf 7 EBX: BMI1 3, AVX2 5, BMI2 8.
  const bool v3 = os_avx && has(l1.ecx, 12) && has(l1.ecx, 22) && has(l1.ecx, 28) && has(l1.ecx, 29) &&
                  has(l7.ebx, 3) && has(l7.ebx, 5) && has(l7.ebx, 8) && has(e1.ecx, 5);
  return v3 ? CpuLevel::kV3 : CpuLevel::kV2;
}
#else
CpuLevel probe() { return CpuLevel::kBaseline; }
#endif

// 0: no cap.
std::atomic<int> g_cap{0};

}  // namespace

CpuLevel detected_cpu_level() {
  static const CpuLevel level = probe();
  return level;
}

CpuLevel cpu_level() {
  const int cap = g_cap.load(std::memory_order_relaxed);
  const CpuLevel detected = detected_cpu_level();
  return cap != 0 && cap < int(detected) ? CpuLevel(cap) : detected;
}

void cap_cpu_level(std::optional<CpuLevel> cap) { g_cap.store(cap ? int(*cap) : 0, std::memory_order_relaxed); }

std::string_view cpu_level_name(CpuLevel level) {
  switch (level) {
    case CpuLevel::kBaseline:
      return "x86-64";
    case CpuLevel::kV2:
      return "x86-64-v2";
    case CpuLevel::kV3:
      return "x86-64-v3";
  }
  return "x86-64";
}

std::optional<CpuLevel> parse_cpu_level(std::string_view name) {
  for (const CpuLevel l : {CpuLevel::kBaseline, CpuLevel::kV2, CpuLevel::kV3}) {
    if (name == cpu_level_name(l)) return l;
  }
  return std::nullopt;
}

}  // namespace soiq
