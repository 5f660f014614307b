#pragma once
// Precompute (docs/DESIGN.md "Queries"; db/store.h): one background thread takes structures from the
// store's durable queue, computes their default features through the FeatureEngine, so that they
// land in the feature cache under the very keys a query's stage 2 reads, and stores the shape values
// among them where stage 1 filters on them (db::stored_feature_names()).
//
// The default features: those shape values on the default grid (GridChoice{}: axis-aligned, 1 mm,
// the default margin), fill rule non-zero; and mean, minimum and maximum inside and in the 3 mm
// shell around it, on every image of the structure's study, nearest-neighbour, on the same grid.
// With the weighted set (soiqd --precompute weighted) also the coverage-weighted features
// (weighted_feature_names(): volume_w_mm3, mean_w, ...) inside, on every image: a coverage
// conversion of the surface each, about 4x a plain one, admitted by the memory budget as a query's
// would be. An open (robust) surface has no coverage and gets none.
//
// Why it is safe beside queries: the thread runs at nice 19 (about 1.5 % of a core against busy
// threads of normal priority, all of any idle core); its conversions are admitted by the memory budget like any other;
// a query never waits for it (a query computes what is missing itself). A structure whose shape features cannot be
// computed is marked failed with the reason (queries then meet the same error and report it); an
// image that fails (another frame of reference, ...) is logged and skipped, the others kept.
//
// Thread-safety: start() once; notify() from any thread; the destructor stops the thread and joins
// it (work in flight is abandoned and stays queued, so the next start resumes it).

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <thread>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/feature_engine.h"

namespace soiq::server {

class PrecomputeWorker {
 public:
  // `set` says which features to compute. `may_run` says whether this soiqd is the one of its
  // replicas that precomputes (it is asked before each batch; always, for a soiqd alone on its store).
  PrecomputeWorker(
      db::Store& store, FeatureEngine& features, db::PrecomputedSet set = db::PrecomputedSet::kDefault,
      std::function<bool()> may_run = [] { return true; })
      : store_(store), features_(features), set_(set), may_run_(std::move(may_run)) {}
  ~PrecomputeWorker();
  PrecomputeWorker(const PrecomputeWorker&) = delete;
  PrecomputeWorker& operator=(const PrecomputeWorker&) = delete;

  // Queues again the structures whose stored values are of an older feature definition (dropping
  // them) or of a smaller set than `set` (keeping them), then starts the thread. Call before
  // serving, so that stage 1 never filters on stale values.
  Status start();
  // Something was queued: look now rather than at the next poll.
  void notify();
  // What one structure's precompute found: the values to store, or the failure. Exposed for tests;
  // the thread calls it for each queued structure.
  Result<db::Precomputed> precompute(const db::StructureRecord& structure);

 private:
  void loop();
  // Computes `ask` for the structure unless the feature cache holds all of it; appends the values
  // computed to `out`'s cache entries and returns every value the plan wants.
  Result<FeatureValues> values(const db::StructureRecord& structure, const std::vector<db::SeriesRecord>& series,
                               FeatureAsk ask, db::Precomputed& out);
  // The coverage-weighted features of the weighted set; an image that fails is logged and skipped.
  Status weighted_values(const db::StructureRecord& structure, const std::vector<db::SeriesRecord>& series,
                         db::Precomputed& out);

  db::Store& store_;
  FeatureEngine& features_;
  const db::PrecomputedSet set_;
  const std::function<bool()> may_run_;
  std::thread thread_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool work_signalled_ = false;
  std::atomic<bool> stopping_{false};
  std::atomic<int64_t> stored_{0};  // structures whose results this worker stored (logged at stop)
};

}  // namespace soiq::server
