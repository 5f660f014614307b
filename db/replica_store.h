#pragma once
// The stage-2 work queue soiqd replicas share on one database, one of the store's three roles
// (db/store.h, docs/SCALE_OUT.md).
//
// The store's contract (db/store.h) holds for every method here: one transaction per write, errors
// as soiq::Status codes, safe to call from many threads at once.

#include <cstdint>
#include <string>
#include <vector>

#include "core/base/status.h"

namespace soiq::db {

// Stage-2 work shared between soiqd replicas on one database (docs/SCALE_OUT.md): a query posts the
// structures whose features it lacks; every live replica claims some, computes them into the
// feature cache, and finishes them; the query waits until none is left, then reads the cache.
struct Stage2Work {
  std::string query_id;
  int64_t structure_id = 0;
  std::string ask;  // what to compute, as the query engine encodes it (opaque to the store)
};

// The replicas' role: 7 methods, each one transaction.
class ReplicaStore {
 public:
  virtual ~ReplicaStore() = default;

  // Times are the database's clock, so replicas on machines whose clocks differ agree. A replica is
  // live while its last heartbeat is at most `live_ms` old.
  //
  // Records that `replica_id` is alive, drops the work posted by replicas that are not (nobody waits
  // for it), and returns the number of live replicas, this one included.
  virtual Result<int> replica_heartbeat(const std::string& replica_id, int64_t live_ms) = 0;
  // The live replica with the smallest id ("" when none is live): the one that runs the work only
  // one replica should run (precompute), chosen again as soon as it falls silent.
  virtual Result<std::string> first_live_replica(int64_t live_ms) = 0;
  // Posts the structures of a query for any replica to compute (one item per structure id; an id
  // given twice is one item).
  virtual Status post_stage2_work(const std::string& replica_id, const std::string& query_id, const std::string& ask,
                                  const std::vector<int64_t>& structure_ids) = 0;
  // Up to `limit` items that no live replica holds (never claimed, or claimed by one that died),
  // oldest first, now held by `replica_id`. Two replicas never get the same item while both live.
  virtual Result<std::vector<Stage2Work>> claim_stage2_work(const std::string& replica_id, int64_t limit,
                                                            int64_t live_ms) = 0;
  // The item is done: its values are in the feature cache, or it failed (the query computes it
  // again itself, and reports the failure as its own). Finishing an item that is gone is no error.
  virtual Status finish_stage2_work(const std::string& query_id, int64_t structure_id) = 0;
  // How many items of the query are not finished.
  virtual Result<int64_t> stage2_work_left(const std::string& query_id) = 0;
  // Drops the query's items that are left (it is done, or gone).
  virtual Status drop_stage2_work(const std::string& query_id) = 0;
};

}  // namespace soiq::db
