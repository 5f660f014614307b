#include "db/sqlite/sqlite_store.h"

#include "db/sqlite/schema_migrations.h"

namespace soiq::db {

Result<std::unique_ptr<SqliteStore>> SqliteStore::open(const std::string& path, const SqliteOptions& options) {
  if (options.busy_timeout_ms < 0) return invalid_argument("busy_timeout_ms must be >= 0");
  if (options.read_connections < 1) return invalid_argument("read_connections must be >= 1");
  if (options.cache_mib < 1) return invalid_argument("cache_mib must be >= 1");
  std::unique_ptr<SqliteStore> store(new SqliteStore());
  SOIQ_ASSIGN_OR_RETURN(store->writer_,
                        Connection::open(path, options.busy_timeout_ms, options.cache_mib, ConnectionRole::kWriter));
  // Migrate before any reader exists, so readers only ever see the current schema.
  SOIQ_RETURN_IF_ERROR(migrate_schema(*store->writer_));
  for (int i = 0; i < options.read_connections; ++i) {
    SOIQ_ASSIGN_OR_RETURN(auto reader,
                          Connection::open(path, options.busy_timeout_ms, options.cache_mib, ConnectionRole::kReader));
    store->free_readers_.push_back(reader.get());
    store->readers_.push_back(std::move(reader));
  }
  return store;
}

SqliteStore::~SqliteStore() {
  // Keeps the query planner's statistics fresh at the cost of a little work on close (SQLite's
  // advice for long-lived connections); failures only cost plan quality, so they are ignored.
  if (writer_) (void)writer_->exec("PRAGMA optimize");
}

Status SqliteStore::read(const std::function<Status(Connection&)>& fn) {
  Connection* c = nullptr;
  {
    std::unique_lock lock(readers_mutex_);
    reader_free_.wait(lock, [&] { return !free_readers_.empty(); });
    c = free_readers_.back();
    free_readers_.pop_back();
  }
  Status s = run_transaction(*c, TransactionKind::kRead, [&] { return fn(*c); });
  {
    std::lock_guard lock(readers_mutex_);
    free_readers_.push_back(c);
  }
  reader_free_.notify_one();
  return s;
}

Status SqliteStore::write(const std::function<Status(Connection&)>& fn) {
  std::lock_guard lock(writer_mutex_);
  return run_transaction(*writer_, TransactionKind::kWrite, [&] { return fn(*writer_); });
}

Result<int> SqliteStore::schema_version() {
  int version = 0;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(version, db::schema_version(c));
    return ok_status();
  }));
  return version;
}

namespace {

// The row count of each table, in the order of Counts' fields.
constexpr char kCountsSql[] = R"sql(
  SELECT (SELECT count(*) FROM patients),
         (SELECT count(*) FROM studies),
         (SELECT count(*) FROM series),
         (SELECT count(*) FROM structures),
         (SELECT count(*) FROM surfaces),
         (SELECT count(*) FROM feature_cache),
         (SELECT count(*) FROM precompute_queue WHERE failure = ''),
         (SELECT count(*) FROM precompute_queue WHERE failure <> ''))sql";

// The distinct modalities of the series, by a skip-scan over the series_modality index: one index
// seek per distinct value, not a pass over every series.
constexpr char kSeriesModalitiesSql[] = R"sql(
  WITH RECURSIVE m(modality) AS (
    SELECT min(modality) FROM series
    UNION ALL
    SELECT (SELECT min(modality) FROM series WHERE modality > m.modality) FROM m WHERE m.modality IS NOT NULL)
  SELECT modality FROM m WHERE modality IS NOT NULL)sql";

}  // namespace

Result<Counts> SqliteStore::counts() {
  Counts n;
  SOIQ_RETURN_IF_ERROR(read([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement st, c.prepare(kCountsSql));
    SOIQ_ASSIGN_OR_RETURN(const bool row, st.step());
    if (!row) return internal_error("count query returned no row");
    n = Counts{st.int64(0), st.int64(1), st.int64(2), st.int64(3), st.int64(4),
               st.int64(5), st.int64(6), st.int64(7), {}};
    SOIQ_ASSIGN_OR_RETURN(Statement modalities, c.prepare(kSeriesModalitiesSql));
    for (;;) {
      SOIQ_ASSIGN_OR_RETURN(const bool more, modalities.step());
      if (!more) break;
      n.series_modalities.push_back(modalities.text(0));
    }
    return ok_status();
  }));
  return n;
}

Result<int64_t> SqliteStore::remove(const Removal& r) {
  switch (r.kind) {
    case Removal::Kind::kStructure:
      return remove_structure(r.structure_id);
    case Removal::Kind::kPatient:
      return remove_patient(r.patient_id);
  }
  return invalid_argument("unknown kind of removal");
}

Result<std::string> SqliteStore::get_blob(BlobKind kind, const std::string& key) {
  return kind == BlobKind::kImage ? image_blob(key) : surface_blob(key);
}

}  // namespace soiq::db
