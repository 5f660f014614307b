#pragma once
// The Store (store.h) on a PostgreSQL database that several soiqd replicas may share:
// docs/DESIGN.md "Storage", docs/SCALE_OUT.md. The records' SQL is SqlStore's (db/sql/sql_store.h),
// the same as SQLite's; this class owns the connection pool and the transactions, and writes and
// reads the feature cache in one statement each (pg_feature_cache.h). The conformance suite
// (tests/db/store_conformance_test.cpp) holds both backends to the same behaviour.
//
// Threads, replicas and transactions: every method may be called from any number of threads, in
// any number of processes on the same database. A method leases a connection from the replica's
// pool (pg_pool.h; DEADLINE_EXCEEDED when none comes free in time) for its whole transaction.
//   - Writes run SERIALIZABLE: they read (is this study another patient's? is this surface stored?)
//     before they write, and two replicas importing the same patient at once must not both insert
//     it. They also take turns, across replicas, on one advisory lock taken before BEGIN: overlapping
//     writers conflicted so often that one could lose all its retries. A transaction PostgreSQL
//     still aborts (SQLSTATE 40001, 40P01: against a writer outside soiqd) runs again after a random
//     wait (pg_transaction), so callers see success or a real error.
//   - Reads of several statements run in one REPEATABLE READ READ ONLY snapshot (a page and its
//     counts agree); reads of one statement run alone, without BEGIN and COMMIT.
//   - Blobs travel in binary, never as hex text.
//
// Beyond SqliteStore: text must be UTF-8 (PostgreSQL refuses other bytes: INVALID_ARGUMENT), and a
// blob is at most 1 GiB (RESOURCE_EXHAUSTED).

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "db/postgres/pg_pool.h"
#include "db/sql/sql_store.h"

namespace soiq::db {

struct PgOptions {
  int connections = 8;                          // the pool's size (soiqd --db-connections)
  std::chrono::milliseconds lease_wait{30000};  // how long a method waits for a connection
  int write_attempts = 10;                      // runs of a write that keeps conflicting
  // Only read the database (soiq-admin verify, beside running replicas): no migration (a store of
  // an older schema is read as it is) and every transaction read only, so any write fails.
  bool read_only = false;
};

class PgStore : public SqlStore {
 public:
  // Connects the pool to `conninfo` (a postgresql:// URI or libpq key=value pairs) and migrates the
  // schema. UNAVAILABLE naming the server when it cannot be reached; FAILED_PRECONDITION when its
  // schema is newer than this code knows; INVALID_ARGUMENT for bad options.
  static Result<std::unique_ptr<PgStore>> open(const std::string& conninfo, const PgOptions& options);

  Result<std::vector<CachedFeature>> cached_features(const std::vector<std::string>& keys,
                                                     const std::vector<std::string>& entries) override;
  using Store::cached_features;
  Status after_bulk_load() override;

 protected:
  Status read(const std::function<Status(SqlSession&)>& fn) override;
  Status write(const std::function<Status(SqlSession&)>& fn) override;
  Status read_one(const std::function<Status(SqlSession&)>& fn) override;
  // READ COMMITTED: a claim's SKIP LOCKED, not serializability, keeps two replicas off one item.
  Status write_queue(const std::function<Status(SqlSession&)>& fn) override;
  Status upsert_cached_features(SqlSession& c, const std::vector<SurfaceFeatures>& batch) override;

 private:
  PgStore() = default;

  std::unique_ptr<PgPool> pool_;
  PgOptions options_;
};

}  // namespace soiq::db
