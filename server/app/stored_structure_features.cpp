#include "server/app/stored_structure_features.h"

#include <algorithm>
#include <chrono>

namespace soiq::server {

Result<StoredStructureFeatures> stored_structure_features(db::Store& store, FeatureEngine& features, WorkerPool& pool,
                                                          int64_t structure_id, const FeatureAsk& ask) {
  SOIQ_ASSIGN_OR_RETURN(const db::StructureRecord s, store.get_structure(structure_id));
  SOIQ_ASSIGN_OR_RETURN(const std::vector<db::SeriesRecord> series, store.list_series(s.study_uid));
  StoredStructureFeatures out;
  SOIQ_ASSIGN_OR_RETURN(out.plan, features.plan(s, series, ask));
  Result<std::vector<db::CachedFeature>> cached = store.cached_features({out.plan.cache_key});
  if (!cached.ok()) {
    return Status(cached.status().code(), "structure " + std::to_string(s.id) + ": " + cached.status().message());
  }
  for (db::CachedFeature& c : *cached) out.values[c.entry] = std::move(c.value);
  out.from_cache = std::all_of(out.plan.wants.begin(), out.plan.wants.end(),
                               [&](const WantedValue& w) { return out.values.count(w.entry) > 0; });
  if (out.from_cache) return out;
  const auto start = std::chrono::steady_clock::now();
  auto work = [&] { return features.compute(out.plan, ask); };
  SOIQ_ASSIGN_OR_RETURN(out.values, pool.call(work));
  out.compute_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace soiq::server
