#include "db/postgres/pg_store.h"

#include "db/postgres/pg_feature_cache.h"
#include "db/postgres/pg_session.h"

namespace soiq::db {

Result<std::unique_ptr<PgStore>> PgStore::open(const std::string& conninfo, const PgOptions& options) {
  if (options.lease_wait.count() < 0) return invalid_argument("PostgreSQL lease wait must be >= 0 ms");
  if (options.write_attempts < 1) return invalid_argument("PostgreSQL write attempts must be >= 1");
  std::unique_ptr<PgStore> store(new PgStore());
  SOIQ_ASSIGN_OR_RETURN(store->pool_, PgPool::open(conninfo, options.connections, options.read_only));
  store->options_ = options;
  return store;
}

namespace {

// The store's writers, in every replica, take turns: overlapping serializable writes conflict
// (a fresh database's tables are scanned whole, so any two do; and writes of one study always
// do), and a writer could lose every retry to a stream of others: 8 threads adding structures
// to 5 patients saw ABORTED after 10 attempts. The lock is taken before BEGIN, so each write's
// snapshot starts after the previous write committed. A session lock: a lost connection drops it.
// The key is arbitrary, the same in every soiqd ("soiq" in ASCII).
constexpr char kWriteLockSql[] = "SELECT pg_advisory_lock(1936681329)";
constexpr char kWriteUnlockSql[] = "SELECT pg_advisory_unlock(1936681329)";

}  // namespace

Status PgStore::write(const std::function<Status(SqlSession&)>& fn) {
  if (options_.read_only) return failed_precondition("the PostgreSQL store is open for reading only");
  SOIQ_ASSIGN_OR_RETURN(PgPool::Lease c, pool_->acquire(options_.lease_wait));
  SOIQ_RETURN_IF_ERROR(c->run(kWriteLockSql, "wait for the store's write turn"));
  PgSession session(*c);
  const Status done = pg_transaction(
      *c, [&] { return fn(session); }, PgIsolation::kSerializable, options_.write_attempts);
  // A connection that cannot say it is done would keep the lock: it is made again, which ends
  // its session and with it the lock.
  if (!c->run(kWriteUnlockSql, "end the store's write turn").ok()) c->reset();
  return done;
}

Status PgStore::read(const std::function<Status(SqlSession&)>& fn) {
  SOIQ_ASSIGN_OR_RETURN(PgPool::Lease c, pool_->acquire(options_.lease_wait));
  PgSession session(*c);
  return pg_transaction(
      *c, [&] { return fn(session); }, PgIsolation::kSnapshotReadOnly);
}

Status PgStore::write_queue(const std::function<Status(SqlSession&)>& fn) {
  if (options_.read_only) return failed_precondition("the PostgreSQL store is open for reading only");
  SOIQ_ASSIGN_OR_RETURN(PgPool::Lease c, pool_->acquire(options_.lease_wait));
  PgSession session(*c);
  return pg_transaction(
      *c, [&] { return fn(session); }, PgIsolation::kReadCommitted, options_.write_attempts);
}

Status PgStore::read_one(const std::function<Status(SqlSession&)>& fn) {
  SOIQ_ASSIGN_OR_RETURN(PgPool::Lease c, pool_->acquire(options_.lease_wait));
  PgSession session(*c);
  return fn(session);
}

Status PgStore::after_bulk_load() {
  SOIQ_ASSIGN_OR_RETURN(PgPool::Lease c, pool_->acquire(options_.lease_wait));
  // Outside a transaction (VACUUM refuses one): sets the rows' hint bits and the visibility map,
  // which the first queries over freshly copied tables would otherwise write (measured: a cold
  // query 3.8 s on a fresh copy, 1.9 s once vacuumed).
  return c->run("VACUUM (ANALYZE)", "vacuum after a bulk load");
}

Status PgStore::upsert_cached_features(SqlSession& c, const std::vector<SurfaceFeatures>& batch) {
  // The sessions of this store are PgSessions (read, write and read_one above make them).
  return pg_put_cached_features(static_cast<PgSession&>(c).connection(), batch);
}

Result<std::vector<CachedFeature>> PgStore::cached_features(const std::vector<std::string>& keys,
                                                            const std::vector<std::string>& entries) {
  std::vector<CachedFeature> out;
  SOIQ_RETURN_IF_ERROR(read_one([&](SqlSession& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(out, pg_cached_features(static_cast<PgSession&>(c).connection(), keys, entries));
    return ok_status();
  }));
  return out;
}

}  // namespace soiq::db
