#pragma once
// The two-stage query (docs/DESIGN.md "Queries"), as named steps:
//   stage 1   one SQL query on indexed columns (Store::stage1), with each candidate's
//             contralateral twin from the same query when an asymmetry is asked;
//   subjects  the structures whose features are needed: candidates and their twins, each once;
//   plan      what each subject needs (grid, images, cache key), nothing decoded, then the
//             feature cache for every plan in one round trip;
//   compute   the misses on the worker pool, in parallel; with other live replicas on the same
//             database, first shared among all of them (shared_stage2.h), then read from the cache;
//   evaluate  each candidate as soon as it and its twin are ready: predicates (AND), then the
//             row streams at once (no order) or waits for the sort (order, then the first limit).
// Progress goes out as work completes (at most every 100 ms, and at the end of each stage).
//
// Asymmetry: a QueryFeature with asymmetry = true is (L - R) / ((L + R) / 2) between the structure
// and its twin, whether or not stage 1 kept the twin; a structure without a twin does not match a
// predicate on an asymmetry and has no value for it.
//
// A structure whose features cannot be computed (no image of the modality in its study, an empty
// shell, ...) does not match; it is counted in QuerySummary::failed, its reason given (first 10),
// and the reasons counted in QuerySummary::skipped (query_skips.h).
//
// Errors: NOT_FOUND, before stage 1, for an image no stored series answers to (image_refs_check.h);
// RESOURCE_EXHAUSTED when stage 1 keeps more than the stage-1 cap; the store's errors;
// CANCELLED or DEADLINE_EXCEEDED when `stop` says so (work in flight is abandoned: workers check
// between structures and between steps); the output's own errors (a closed stream) unchanged.
// Thread-safety: one engine serves concurrent queries; a run uses the calling thread and the pool.

#include <functional>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/feature_engine.h"
#include "server/app/image_refs_check.h"
#include "server/app/query.h"
#include "server/app/shared_stage2.h"
#include "server/util/worker_pool.h"

namespace soiq::server {

struct QueryLimits {
  int result_cap = 10000;
  int64_t stage1_cap = 100000;
};

class QueryEngine {
 public:
  // `sharing`: the replicas' shared stage 2, or null for a soiqd alone on its store.
  QueryEngine(db::Store& store, FeatureEngine& features, WorkerPool& pool, QueryLimits limits,
              SharedStage2* sharing = nullptr)
      : store_(store), features_(features), pool_(pool), sharing_(sharing), limits_(limits) {}

  // `stop` returns a non-OK status (CANCELLED, DEADLINE_EXCEEDED) once the caller is gone or out
  // of time. Rows and progress go to `out`; the summary is returned.
  Result<QuerySummary> run(const Query& query, const std::function<Status()>& stop, const QueryOutput& out);

  const QueryLimits& limits() const { return limits_; }

 private:
  db::Store& store_;
  FeatureEngine& features_;
  WorkerPool& pool_;
  SharedStage2* sharing_;
  const QueryLimits limits_;
  ImageRefsCheck image_refs_;
};

}  // namespace soiq::server
