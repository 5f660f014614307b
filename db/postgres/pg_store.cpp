#include "db/postgres/pg_store.h"

#include <utility>

#include "db/postgres/pg_feature_cache.h"
#include "db/postgres/pg_store_writes.h"
#include "db/sql/record_sql.h"
#include "db/validate_records.h"

namespace soiq::db {

Result<std::unique_ptr<PgStore>> PgStore::open(const std::string& conninfo, const PgOptions& options) {
  if (options.lease_wait.count() < 0) return invalid_argument("PostgreSQL lease wait must be >= 0 ms");
  if (options.write_attempts < 1) return invalid_argument("PostgreSQL write attempts must be >= 1");
  std::unique_ptr<PgStore> store(new PgStore());
  SOIQ_ASSIGN_OR_RETURN(store->pool_, PgPool::open(conninfo, options.connections));
  store->options_ = options;
  return store;
}

Status PgStore::write(const std::function<Status(PgConnection&)>& fn) {
  SOIQ_ASSIGN_OR_RETURN(PgPool::Lease c, pool_->acquire(options_.lease_wait));
  return pg_transaction(
      *c, [&] { return fn(*c); }, PgIsolation::kSerializable, options_.write_attempts);
}

Status PgStore::read(const std::function<Status(PgConnection&)>& fn) {
  SOIQ_ASSIGN_OR_RETURN(PgPool::Lease c, pool_->acquire(options_.lease_wait));
  return pg_transaction(
      *c, [&] { return fn(*c); }, PgIsolation::kSnapshotReadOnly);
}

Status PgStore::read_one(const std::function<Status(PgConnection&)>& fn) {
  SOIQ_ASSIGN_OR_RETURN(PgPool::Lease c, pool_->acquire(options_.lease_wait));
  return fn(*c);
}

Result<ImportedBatch> PgStore::import_batch(const ImportBatch& b) {
  for (const NewSeries& s : b.series) SOIQ_RETURN_IF_ERROR(validate_new_series(s));
  for (const NewStructure& s : b.structures) SOIQ_RETURN_IF_ERROR(validate_new_structure(s));
  ImportedBatch out;
  SOIQ_RETURN_IF_ERROR(write([&](PgConnection& c) -> Status {
    out = {};  // a retried transaction starts again
    // Series first: a structure's study then already has its series' modalities for stage 1.
    for (const NewSeries& s : b.series) {
      SOIQ_ASSIGN_OR_RETURN(const bool replaced, pg_insert_series(c, s));
      out.series_replaced.push_back(replaced);
    }
    for (const NewStructure& s : b.structures) {
      SOIQ_ASSIGN_OR_RETURN(AddedStructure added, pg_insert_structure(c, s));
      out.structures.push_back(std::move(added));
    }
    return ok_status();
  }));
  return out;
}

Status PgStore::put_cached_features(const std::string& surface_sha256, const std::vector<CachedFeature>& entries) {
  return put_cached_features(std::vector<SurfaceFeatures>{{surface_sha256, entries}});
}

Status PgStore::put_cached_features(const std::vector<SurfaceFeatures>& batch) {
  for (const SurfaceFeatures& s : batch) SOIQ_RETURN_IF_ERROR(validate_cache_entries(s.surface_sha256, s.entries));
  // One statement: atomic by itself, and an upsert, so no transaction of its own is needed.
  return read_one([&](PgConnection& c) { return pg_put_cached_features(c, batch); });
}

Result<std::vector<CachedFeature>> PgStore::cached_features(const std::vector<std::string>& keys,
                                                            const std::vector<std::string>& entries) {
  std::vector<CachedFeature> out;
  SOIQ_RETURN_IF_ERROR(read_one([&](PgConnection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(out, pg_cached_features(c, keys, entries));
    return ok_status();
  }));
  return out;
}

Result<Counts> PgStore::counts() {
  Counts n;
  SOIQ_RETURN_IF_ERROR(read([&](PgConnection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(const PgResult r, c.exec(kCountsSql, {}, "count the records"));
    n = Counts{r.int64(0, 0), r.int64(0, 1), r.int64(0, 2),
               r.int64(0, 3), r.int64(0, 4), r.int64(0, 5),
               r.int64(0, 6), r.int64(0, 7), {}};
    SOIQ_ASSIGN_OR_RETURN(const PgResult m, c.exec(kSeriesModalitiesSql, {}, "list the series' modalities"));
    for (int i = 0; i < m.rows(); ++i) n.series_modalities.push_back(m.text(i, 0));
    return ok_status();
  }));
  return n;
}

}  // namespace soiq::db
