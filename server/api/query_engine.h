#pragma once
// The two-stage query (DESIGN.md "Queries"). Stage 1 is one SQL query on indexed columns
// (Store::stage1). Stage 2 plans the features every candidate needs, reads what the feature cache
// already has in one round trip, computes the rest on the worker pool in parallel, evaluates the
// predicates (AND) and either streams matching rows as they are ready (no order) or sorts them and
// streams the first `limit`. Progress events go out as work completes (at most every 100 ms, and
// at the end of each stage); a summary closes the stream.
//
// Asymmetry: a FeatureRef with asymmetry = true is (L − R) / ((L + R) / 2) between the structure
// and its contralateral twin — same study, same name (case-insensitive), the other laterality.
// Twins are computed too, whether or not stage 1 kept them; a structure without a twin does not
// match a predicate on an asymmetry and has no value for it.
//
// A structure whose features cannot be computed (no image of the modality in its study, an empty
// shell, ...) does not match; it is counted in summary.failed and its reason given (first 10).
//
// Errors (the stream ends with them): INVALID_ARGUMENT for a malformed request (unknown feature,
// bad region, array feature in a predicate, bad dates); RESOURCE_EXHAUSTED when stage 1 keeps more
// than the stage-1 cap; CANCELLED / DEADLINE_EXCEEDED when `stop` says so — work in flight is
// abandoned (workers check between structures and between steps).

#include <functional>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/feature_engine.h"
#include "server/util/worker_pool.h"
#include "soiq/v1/soiq.pb.h"

namespace soiq::server {

struct QueryLimits {
  int result_cap = 10000;
  int64_t stage1_cap = 100000;
};

class QueryEngine {
 public:
  QueryEngine(db::Store& store, FeatureEngine& features, WorkerPool& pool, QueryLimits limits)
      : store_(store), features_(features), pool_(pool), limits_(limits) {}

  // `stop` returns a non-OK status (CANCELLED, DEADLINE_EXCEEDED) once the client is gone or out
  // of time; `emit` writes one event and returns false when the stream is broken.
  Status run(const v1::QueryRequest& request, const std::function<Status()>& stop,
             const std::function<bool(const v1::QueryEvent&)>& emit);

 private:
  db::Store& store_;
  FeatureEngine& features_;
  WorkerPool& pool_;
  const QueryLimits limits_;
};

}  // namespace soiq::server
