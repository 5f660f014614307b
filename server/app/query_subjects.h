#pragma once
// Internal to query_engine.cpp: the state a query run keeps per structure, and what its workers
// hand back, in a header of their own so the run's steps read without them.

#include <atomic>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/feature_engine.h"

namespace soiq::server::query_run {

// One structure whose features the query needs: a candidate, or a candidate's twin.
struct Subject {
  db::StructureRecord structure;
  std::optional<FeaturePlan> plan;
  Status error;
  // Shared, not copied: subjects of one surface (and grid) read the same cached values.
  std::shared_ptr<const FeatureValues> values;
  // The query's features in its order, each a value in `values` or null: resolved once when the
  // subject is ready, so evaluating a candidate looks up no entry names.
  std::vector<const std::vector<double>*> asked;
  bool ready = false;
  std::vector<size_t> dependents;  // candidates waiting for this subject
};

// What the workers hand back to the query's thread: a subject's computed features and the cache
// entries still to be written.
struct Computed {
  size_t idx;
  Result<FeatureValues> values;
  db::SurfaceFeatures to_store;
};

struct Completions {
  std::mutex mutex;
  std::condition_variable wake;
  std::deque<Computed> done;
  std::atomic<bool> cancelled{false};
};

}  // namespace soiq::server::query_run
