#include "bench/method_run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "bench/cpu_affinity.h"

namespace soiq::bench {

Result<MethodRun> run_method(Method method, const TriangleMesh& mesh, const Mask& reference, int threads, int runs,
                             int pin_cpu) {
  const Result<Conversion> conversion = prepare_conversion(method, mesh, reference.geometry, threads);
  if (!conversion.ok()) return conversion.status();
  std::optional<ScopedAffinity> affinity;
  if (threads == 1) affinity.emplace(pin_cpu);
  Result<Timed> timed = time_conversion(*conversion, runs);
  affinity.reset();
  if (!timed.ok()) {
    return Status(timed.status().code(), std::string(method_name(method)) + ": " + timed.status().message());
  }
  const Result<Agreement> agreement = mask_agreement(timed->mask, reference);
  if (!agreement.ok()) return agreement.status();
  MethodRun out{std::move(timed).value(), *agreement};
  out.timed.mask = Mask{};  // tables keep only figures
  return out;
}

std::vector<Result<MethodRun>> run_methods_interleaved(const std::vector<MethodSpec>& specs, const TriangleMesh& mesh,
                                                       const Mask& reference, int runs, int pin_cpu, double budget_ms) {
  std::vector<Result<Conversion>> conversions;
  for (const MethodSpec& s : specs) {
    conversions.push_back(prepare_conversion(s.method, mesh, reference.geometry, s.threads));
  }
  std::vector<std::vector<double>> ms(specs.size());
  std::vector<Mask> last(specs.size());
  std::vector<Status> failure(specs.size());
  std::vector<double> spent(specs.size(), 0);
  for (int r = 0; r < runs; ++r) {
    for (size_t m = 0; m < specs.size(); ++m) {
      if (!conversions[m].ok() || !failure[m].ok() || spent[m] >= budget_ms) continue;
      last[m] = Mask{};  // release the previous result outside the timed region
      // A multi-threaded run first makes one untimed call, unpinned: it wakes core's pool worker
      // (created by the first such call, bound to another CPU than pin_cpu; core/base/run_tasks.h), as
      // in a server converting structure after structure. Then its calling thread is pinned too,
      // so caller and worker never share a core (unpinned, the scheduler sometimes left the caller
      // on the worker's CPU for a whole row: 1.2-1.5x instead of 1.9x).
      if (specs[m].threads > 1) static_cast<void>((*conversions[m])());
      std::optional<ScopedAffinity> affinity;
      affinity.emplace(pin_cpu);
      const auto t0 = std::chrono::steady_clock::now();
      Result<Mask> mask = (*conversions[m])();
      const auto t1 = std::chrono::steady_clock::now();
      affinity.reset();
      if (!mask.ok()) {
        failure[m] =
            Status(mask.status().code(), std::string(method_name(specs[m].method)) + ": " + mask.status().message());
        continue;
      }
      ms[m].push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
      spent[m] += ms[m].back();
      last[m] = std::move(mask).value();
    }
  }
  std::vector<Result<MethodRun>> out;
  for (size_t m = 0; m < specs.size(); ++m) {
    if (!conversions[m].ok()) {
      out.push_back(conversions[m].status());
      continue;
    }
    if (!failure[m].ok()) {
      out.push_back(failure[m]);
      continue;
    }
    std::sort(ms[m].begin(), ms[m].end());
    const size_t n = ms[m].size();
    MethodRun run;
    run.timed.min_ms = ms[m].front();
    run.timed.median_ms = n % 2 ? ms[m][n / 2] : 0.5 * (ms[m][n / 2 - 1] + ms[m][n / 2]);
    run.timed.runs = int(n);
    const Result<Agreement> agreement = mask_agreement(last[m], reference);
    if (!agreement.ok()) {
      out.push_back(agreement.status());
      continue;
    }
    run.vs_reference = *agreement;
    out.push_back(std::move(run));
  }
  return out;
}

std::string time_cell(const Result<MethodRun>& r) {
  if (!r.ok()) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.1f", r->timed.min_ms);
  return buf;
}

std::string agreement_cell(const Result<MethodRun>& r) {
  if (!r.ok()) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6f (%lld)", r->vs_reference.iou, (long long)r->vs_reference.differing);
  return buf;
}

}  // namespace soiq::bench
