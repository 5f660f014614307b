#pragma once
// The Store (store.h) on one SQLite file: docs/DESIGN.md "Storage". The records' SQL is SqlStore's
// (db/sql/sql_store.h, shared with PostgreSQL); this class owns the file's connections and
// transactions, and the schema and its migrations (schema_migrations.cpp).
//
// Threads and mutual exclusion: every method may be called from any number of threads. Writes go
// through one writer connection guarded by a mutex (SQLite has one writer at a time anyway, and
// BEGIN IMMEDIATE makes each write take the lock up front). Reads take a connection from a pool
// of `read_connections` readers (waiting when all are busy); WAL lets them run while a write is in
// progress, and each read sees one committed snapshot. A write is visible to every read that
// starts after the write method returned.
//
// Other processes may open the same file (e.g. a backup or the CLI); their locks count against
// the busy timeout, past which a method returns UNAVAILABLE.

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "db/sql/sql_store.h"
#include "db/sqlite/sqlite_connection.h"

namespace soiq::db {

struct SqliteOptions {
  int busy_timeout_ms = 5000;  // how long a method waits for another process's lock
  int read_connections = 4;    // >= 1; more than the worker threads that read at once gains nothing
  int cache_mib = 64;          // page cache per connection, so stage 1 reads memory, not the file
  // Only read the file (soiq-admin verify, beside a running soiqd): no writer connection, no
  // migration (a store of an older schema is read as it is), and every write FAILED_PRECONDITION.
  // The file must exist and hold a store of a schema version this code knows.
  bool read_only = false;
};

class SqliteStore : public SqlStore {
 public:
  // Opens (creating if absent) the database at `path` and migrates it to the current schema.
  // FAILED_PRECONDITION (naming the path) when the file is not a SQLite database or cannot be
  // opened, or when its schema version is newer than this code knows (both versions named); read
  // only, also when it holds no store (schema version 0).
  // INVALID_ARGUMENT for bad options.
  static Result<std::unique_ptr<SqliteStore>> open(const std::string& path, const SqliteOptions& options);
  ~SqliteStore() override;

  // The schema version of the open database (latest_schema_version() after open, unless read only).
  Result<int> schema_version();
  // The EXPLAIN QUERY PLAN lines ("SEARCH r USING INDEX …") of stage1's id query for `f`: for the
  // tests that every stage-1 filter is an index search, and for diagnosing a slow one.
  Result<std::vector<std::string>> stage1_plan(const Stage1Filter& f, int64_t limit);

 protected:
  Status read(const std::function<Status(SqlSession&)>& fn) override;
  Status write(const std::function<Status(SqlSession&)>& fn) override;

 private:
  SqliteStore() = default;

  // The units of work on the connections themselves.
  Status read_connection(const std::function<Status(Connection&)>& fn);
  Status write_connection(const std::function<Status(Connection&)>& fn);

  std::mutex writer_mutex_;
  std::unique_ptr<Connection> writer_;

  std::mutex readers_mutex_;
  std::condition_variable reader_free_;
  std::vector<std::unique_ptr<Connection>> readers_;
  std::vector<Connection*> free_readers_;
};

}  // namespace soiq::db
