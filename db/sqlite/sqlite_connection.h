#pragma once
// One SQLite connection with soiq's settings and a cache of prepared statements. A connection is
// used by one thread at a time; SqliteStore (sqlite_store.h) provides that mutual exclusion.
//
// Settings, applied on open: busy timeout, page cache size, journal_mode=WAL (readers never block the writer and
// vice versa), foreign_keys=ON, synchronous=FULL (a commit is on disk before it is acknowledged,
// so a killed server or a power cut loses nothing acknowledged). A reader connection also sets
// query_only=ON, so a bug cannot write through it.

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>

#include "core/base/status.h"
#include "db/sqlite/sqlite_statement.h"

struct sqlite3;
struct sqlite3_stmt;

namespace soiq::db {

enum class ConnectionRole { kWriter, kReader };

class Connection {
 public:
  // Creates the file when the writer opens a path that does not exist. Errors name the path:
  // FAILED_PRECONDITION when the file is not a SQLite database or cannot be opened.
  static Result<std::unique_ptr<Connection>> open(const std::string& path, int busy_timeout_ms, int cache_mib,
                                                  ConnectionRole role);
  ~Connection();
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  // A prepared statement for `sql`, from the cache when it was prepared before and is not in use.
  Result<Statement> prepare(std::string_view sql);
  // Runs one or more statements that return no rows (schema, BEGIN/COMMIT, pragmas).
  Status exec(const std::string& sql);

  sqlite3* handle() const { return db_; }
  const std::string& path() const { return path_; }

 private:
  struct CachedStatement {
    sqlite3_stmt* stmt = nullptr;
    bool in_use = false;
  };
  Connection(sqlite3* db, std::string path) : db_(db), path_(std::move(path)) {}

  sqlite3* db_;
  std::string path_;
  // std::map: node addresses are stable, so a Statement can hold &in_use.
  std::map<std::string, CachedStatement, std::less<>> cache_;
};

enum class TransactionKind {
  kRead,   // BEGIN (deferred): one consistent snapshot for every statement of fn
  kWrite,  // BEGIN IMMEDIATE: takes the write lock up front, so fn never deadlocks upgrading
};

// Runs fn inside a transaction on `c`: commits when fn returns OK, rolls back on any error (fn's
// status is returned). A busy database past the timeout is UNAVAILABLE.
Status run_transaction(Connection& c, TransactionKind kind, const std::function<Status()>& fn);

}  // namespace soiq::db
