#include "bench/method_run.h"

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
