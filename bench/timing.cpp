#include "bench/timing.h"

#include <algorithm>
#include <chrono>
#include <vector>

namespace soiq::bench {

Result<Timed> time_conversion(const Conversion& conversion, int runs, double budget_ms) {
  if (runs < 1) return invalid_argument("--runs must be >= 1");
  std::vector<double> ms;
  Timed out;
  double total_ms = 0;
  for (int r = 0; r < runs && total_ms < budget_ms; ++r) {
    if (r > 0) out.mask = Mask{};  // release the previous result outside the timed region
    const auto t0 = std::chrono::steady_clock::now();
    Result<Mask> mask = conversion();
    const auto t1 = std::chrono::steady_clock::now();
    if (!mask.ok()) return mask.status();
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    total_ms += ms.back();
    out.mask = std::move(mask).value();
  }
  std::sort(ms.begin(), ms.end());
  out.min_ms = ms.front();
  out.median_ms = ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
  out.runs = int(ms.size());
  return out;
}

}  // namespace soiq::bench
