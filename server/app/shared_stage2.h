#pragma once
// Stage 2 shared between soiqd replicas on one database (docs/SCALE_OUT.md): a replica that has
// many structures to compute for a query posts them to the store's work queue and waits; every
// live replica, the poster too, claims items, computes their features through its FeatureEngine
// into the shared feature cache, and finishes them. The poster then reads the cache like a warm
// query, so its rows are those of a single replica: every value comes from the same deterministic
// computation, whoever ran it.
//
// A replica that dies holds its claims no longer than `live` after its last heartbeat: the others
// claim them again (db::Store::claim_stage2_work). An item that fails on another replica is
// finished all the same; the poster computes it again itself and reports the failure as its own.
//
// Two threads per replica: one heartbeat (every third of `live`; it also says whether this replica
// leads, see leads()), one claimer (claims as many items
// as the worker pool has threads, runs them on the pool, claims again when they are done; polls
// every 25 ms while the queue is empty).
//
// Errors: share() returns the store's errors, and stop()'s (CANCELLED, DEADLINE_EXCEEDED: the
// query's items are dropped). start() the first heartbeat's.
// Thread-safety: start() once; share() from any number of threads; the destructor stops both
// threads (items in flight are abandoned: others claim them once this replica is silent).

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/base/status.h"
#include "db/store.h"
#include "server/app/feature_engine.h"
#include "server/util/worker_pool.h"

namespace soiq::server {

struct SharingOptions {
  std::string replica_id;                // unique among the replicas of the database
  std::chrono::milliseconds live{3000};  // a replica silent for this long is dead
};

class SharedStage2 {
 public:
  SharedStage2(db::Store& store, FeatureEngine& features, WorkerPool& pool, SharingOptions options)
      : store_(store), features_(features), pool_(pool), options_(std::move(options)) {}
  ~SharedStage2();
  SharedStage2(const SharedStage2&) = delete;
  SharedStage2& operator=(const SharedStage2&) = delete;

  Status start();

  // Live replicas at the last heartbeat, this one included (1 before start()).
  int live_replicas() const { return live_.load(); }
  // Whether this replica is the first live one (db::Store::first_live_replica) at the last
  // heartbeat: the one that runs precompute, so that the replicas do not all compute it.
  bool leads() const { return leads_.load(); }

  // Posts the structures (with what to compute) and waits until every one is finished, calling
  // `progress(finished)` as they are (at most every 100 ms). Returns early, OK, when nothing has
  // finished for ten times `live` (at least 10 s): the caller computes what is left.
  Status share(const FeatureAsk& ask, const std::vector<int64_t>& structure_ids, const std::function<Status()>& stop,
               const std::function<Status(int64_t finished)>& progress);

  // Items this replica computed for any query (its share of the work), since start.
  int64_t items_computed() const { return computed_.load(); }

 private:
  void heartbeat_loop();
  void claim_loop();
  void compute(const db::Stage2Work& item);
  bool sleep_unless_stopping(std::chrono::milliseconds d);

  db::Store& store_;
  FeatureEngine& features_;
  WorkerPool& pool_;
  const SharingOptions options_;
  std::atomic<int> live_{1};
  std::atomic<bool> leads_{true};
  std::atomic<int64_t> computed_{0};
  std::atomic<bool> cancelled_{false};  // for computations in flight at shutdown

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;
  int in_flight_ = 0;  // claimed items not yet finished by this replica
  std::thread heartbeat_, claimer_;
};

// A replica id unique enough for one database: host name, process id and a random part.
std::string default_replica_id();

}  // namespace soiq::server
