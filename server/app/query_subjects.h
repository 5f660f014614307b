#pragma once
// Internal to query_engine.cpp: the state a query run keeps per structure, what its workers hand
// back, and a candidate's values read from its subjects, in a file of their own so the run's steps
// read without them.

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

// Subject s's value of the query's feature f (Subject::asked), or null when it has none.
const std::vector<double>* asked_value(size_t f, const Subject& s);

// A candidate's value of the query's feature f, read from its subject and, for an asymmetry
// feature, its twin's (null when it has none): one number, what predicates and the order read,
// without a copy; or the value as its row sends it. Nothing when it cannot be had.
std::optional<double> candidate_scalar(size_t f, bool asymmetry, const Subject& own, const Subject* twin);
std::optional<std::vector<double>> candidate_value(size_t f, bool asymmetry, const Subject& own, const Subject* twin);

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
