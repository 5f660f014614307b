#include "db/sqlite/sqlite_store.h"

#include "db/sql/stage1_sql.h"
#include "db/sqlite/schema_migrations.h"
#include "db/sqlite/sqlite_session.h"
#include "db/validate_records.h"

namespace soiq::db {

Result<std::unique_ptr<SqliteStore>> SqliteStore::open(const std::string& path, const SqliteOptions& options) {
  if (options.busy_timeout_ms < 0) return invalid_argument("busy_timeout_ms must be >= 0");
  if (options.read_connections < 1) return invalid_argument("read_connections must be >= 1");
  if (options.cache_mib < 1) return invalid_argument("cache_mib must be >= 1");
  std::unique_ptr<SqliteStore> store(new SqliteStore());
  if (!options.read_only) {
    SOIQ_ASSIGN_OR_RETURN(store->writer_,
                          Connection::open(path, options.busy_timeout_ms, options.cache_mib, ConnectionRole::kWriter));
    // Migrate before any reader exists, so readers only ever see the current schema.
    SOIQ_RETURN_IF_ERROR(migrate_schema(*store->writer_));
  }
  for (int i = 0; i < options.read_connections; ++i) {
    SOIQ_ASSIGN_OR_RETURN(auto reader,
                          Connection::open(path, options.busy_timeout_ms, options.cache_mib, ConnectionRole::kReader));
    store->free_readers_.push_back(reader.get());
    store->readers_.push_back(std::move(reader));
  }
  if (options.read_only) SOIQ_RETURN_IF_ERROR(store->read_connection(check_schema_readable));
  return store;
}

SqliteStore::~SqliteStore() {
  // Keeps the query planner's statistics fresh at the cost of a little work on close (SQLite's
  // advice for long-lived connections); failures only cost plan quality, so they are ignored.
  if (writer_) (void)writer_->exec("PRAGMA optimize");
}

Status SqliteStore::read_connection(const std::function<Status(Connection&)>& fn) {
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

Status SqliteStore::write_connection(const std::function<Status(Connection&)>& fn) {
  if (!writer_) return failed_precondition("the store '" + readers_.front()->path() + "' is open for reading only");
  std::lock_guard lock(writer_mutex_);
  return run_transaction(*writer_, TransactionKind::kWrite, [&] { return fn(*writer_); });
}

Status SqliteStore::read(const std::function<Status(SqlSession&)>& fn) {
  return read_connection([&](Connection& c) {
    SqliteSession session(c);
    return fn(session);
  });
}

Status SqliteStore::write(const std::function<Status(SqlSession&)>& fn) {
  return write_connection([&](Connection& c) {
    SqliteSession session(c);
    return fn(session);
  });
}

Result<int> SqliteStore::schema_version() {
  int version = 0;
  SOIQ_RETURN_IF_ERROR(read_connection([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(version, db::schema_version(c));
    return ok_status();
  }));
  return version;
}

Result<std::vector<std::string>> SqliteStore::stage1_plan(const Stage1Filter& f, int64_t limit) {
  SOIQ_RETURN_IF_ERROR(validate_stage1_filter(f));
  const SqlConditions where = stage1_conditions(f, SqlDialect::kSqlite);
  std::vector<std::string> plan;
  SOIQ_RETURN_IF_ERROR(read_connection([&](Connection& c) -> Status {
    SOIQ_ASSIGN_OR_RETURN(Statement q, c.prepare("EXPLAIN QUERY PLAN " + stage1_ids_sql(where, f, limit + 1)));
    where.bind(q);
    while (true) {
      SOIQ_ASSIGN_OR_RETURN(const bool row, q.step());
      if (!row) break;
      plan.push_back(q.text(3));
    }
    return ok_status();
  }));
  return plan;
}

}  // namespace soiq::db
